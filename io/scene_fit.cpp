#include "dnurbs/io/scene_fit.h"

#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/design/dnurbs_fitting.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/io/mesh_import.h"
#include "dnurbs/nurbs/shape_generators.h"

namespace dnurbs {

namespace {

// The centroid and principal axes of the points, largest spread first (columns).
struct PrincipalFrame {
  Eigen::RowVector3d centroid;
  Eigen::Matrix3d axes;
};

PrincipalFrame principal_frame(const Eigen::MatrixX3d& points) {
  check_points(points, "points to fit");
  PrincipalFrame frame;
  frame.centroid = points.colwise().mean();
  const Eigen::MatrixX3d centred = points.rowwise() - frame.centroid;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred.transpose() * centred);
  frame.axes = eigen.eigenvectors().rowwise().reverse();  // eigenvalues come increasing
  return frame;
}

void check_start(int degree, int spans) {
  if (degree < 1 || spans < 1) {
    throw make_error("a fit needs degree >= 1 and spans >= 1, got degree ", degree, " and spans ",
                     spans);
  }
}

DNurbsFitSettings fit_settings(const SceneFit& fit) {
  DNurbsFitSettings settings;
  settings.smoothness = fit.smoothness;
  settings.max_iterations = fit.iterations;
  return settings;
}

}  // namespace

Eigen::MatrixX3d read_fit_points(const std::filesystem::path& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".xyz" || extension == ".txt" || extension == ".csv") {
    return load_points(path);
  }
  const std::vector<TriangleMesh> meshes = import_meshes(path);
  try {
    return mesh_vertices(meshes);
  } catch (const Error& error) {
    throw make_error(path.string(), ": ", error.what());
  }
}

NurbsSurface principal_plane_surface(const Eigen::MatrixX3d& points, int degree, int spans) {
  check_start(degree, spans);
  const PrincipalFrame frame = principal_frame(points);
  const Eigen::MatrixX3d centred = points.rowwise() - frame.centroid;
  const Eigen::VectorXd along_u = centred * frame.axes.col(0);
  const Eigen::VectorXd along_v = centred * frame.axes.col(1);
  const KnotVector knots = KnotVector::clamped_uniform(degree, spans + degree);
  const int n = knots.control_point_count();
  const std::vector<double> xi = greville_abscissae(knots);
  Eigen::MatrixX3d control(n * n, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = along_u.minCoeff() +
                       xi[static_cast<size_t>(i)] * (along_u.maxCoeff() - along_u.minCoeff());
      const double y = along_v.minCoeff() +
                       xi[static_cast<size_t>(j)] * (along_v.maxCoeff() - along_v.minCoeff());
      control.row(i * n + j) =
          frame.centroid + (x * frame.axes.col(0) + y * frame.axes.col(1)).transpose();
    }
  }
  return NurbsSurface(knots, knots, control);
}

NurbsCurve principal_axis_curve(const Eigen::MatrixX3d& points, int degree, int spans) {
  check_start(degree, spans);
  const PrincipalFrame frame = principal_frame(points);
  const Eigen::VectorXd along = (points.rowwise() - frame.centroid) * frame.axes.col(0);
  const KnotVector knots = KnotVector::clamped_uniform(degree, spans + degree);
  const int n = knots.control_point_count();
  const std::vector<double> xi = greville_abscissae(knots);
  Eigen::MatrixX3d control(n, 3);
  for (int i = 0; i < n; ++i) {
    const double x =
        along.minCoeff() + xi[static_cast<size_t>(i)] * (along.maxCoeff() - along.minCoeff());
    control.row(i) = frame.centroid + x * frame.axes.col(0).transpose();
  }
  return NurbsCurve(knots, control);
}

NurbsCurve fit_scene_curve(const Eigen::MatrixX3d& points, const SceneFit& fit,
                           const DNurbsCurveMaterial& material, const DNurbsSettings& settings) {
  const DNurbsCurve model(principal_axis_curve(points, fit.degree, fit.spans), material, settings);
  return model.curve(fit_dnurbs_curve(model, points, fit_settings(fit)).coordinates);
}

NurbsSurface fit_scene_surface(const Eigen::MatrixX3d& points, const SceneFit& fit,
                               const DNurbsSurfaceMaterial& material,
                               const DNurbsSettings& settings) {
  const DNurbsSurface model(principal_plane_surface(points, fit.degree, fit.spans), material,
                            settings);
  return model.surface(fit_dnurbs_surface(model, points, fit_settings(fit)).coordinates);
}

void fit_initial_shapes(Scene& scene) {
  for (size_t i = 0; i < scene.models.size(); ++i) {
    SceneModelSpec& spec = *scene.models[i].spec;
    const SceneFit* fit = spec.pending_fit();
    if (fit == nullptr) {
      continue;
    }
    const std::string path = scene.source + ": models[" + std::to_string(i) + "].fit";
    std::filesystem::path file = fit->points;
    if (file.is_relative()) {
      file = scene.directory / file;
    }
    Eigen::MatrixX3d points;
    try {
      points = read_fit_points(file);
    } catch (const Error& error) {
      throw make_error(path, ".points: ", error.what());
    }
    try {
      spec.run_fit(points);
    } catch (const Error& error) {
      throw make_error(path, ": ", error.what());
    }
  }
}

}  // namespace dnurbs
