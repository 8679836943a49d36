#include "dnurbs/dynamics/core/model_tessellation.h"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/memory_budget.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/parametric_surface_tessellation.h"
#include "dnurbs/surface/restricted_mesh.h"
#include "dnurbs/surface/tessellation.h"

namespace dnurbs {
namespace {

void check_coordinates(const Model& model, ConstVectorRef q) {
  if (q.size() != model.coordinate_count()) {
    throw make_error("model tessellation: q has ", q.size(), " entries, the model ",
                     model.coordinate_count());
  }
}

// A degree-1 NURBS curve through the points, knots at the uniform parameters k / segments
// (periodic when closed), so that sample_curve at `segments` returns the points themselves.
NurbsCurve polyline(const Eigen::MatrixX3d& points, bool closed) {
  const int count = static_cast<int>(points.rows());
  const int segments = closed ? count : count - 1;
  std::vector<double> knots;
  if (closed) {
    for (int k = 0; k <= segments; ++k) {
      knots.push_back(static_cast<double>(k) / segments);
    }
    return NurbsCurve(KnotVector::periodic(1, knots), points);
  }
  knots.push_back(0.0);
  for (int k = 0; k <= segments; ++k) {
    knots.push_back(static_cast<double>(k) / segments);
  }
  knots.push_back(1.0);
  return NurbsCurve(KnotVector(1, knots), points);
}

// Positions at `segments` + 1 uniform parameters over the domain (`segments` when closed).
Eigen::MatrixX3d sampled_positions(const Model& model, ConstVectorRef q,
                                   const ParameterDomain& domain, int segments) {
  const bool closed = domain.periodic_u;
  Eigen::MatrixX3d points(closed ? segments : segments + 1, 3);
  for (int k = 0; k < points.rows(); ++k) {
    const double u = domain.u_at(static_cast<double>(k) / segments);
    points.row(k) = model.position(q, Eigen::Vector2d(u, 0.0)).transpose();
  }
  return points;
}

double extent_radius(const Eigen::MatrixX3d& points) {
  const double extent = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  return extent > 0.0 ? 0.01 * extent : 1e-3;
}

}  // namespace

TriangleMesh tessellate_model(const Model& model, ConstVectorRef q,
                              const ModelTessellationSettings& settings, std::string name) {
  check_coordinates(model, q);
  // Every model's mesh has at most about (segments_u + 1) (segments_v + 1) vertices (a curve's
  // tube: (segments + 1) sides), two triangles per cell: checked before anything is allocated
  const bool curve = model.parametric_dimension() == 1;
  const double columns = static_cast<double>(settings.segments_u) + 1.0;
  const double rows = curve ? static_cast<double>(settings.tube_sides)
                            : static_cast<double>(settings.segments_v) + 1.0;
  check_memory_budget(triangle_mesh_bytes(columns * rows, 2.0 * columns * rows),
                      "a mesh of " + std::to_string(settings.segments_u) + " x " +
                          std::to_string(curve ? settings.tube_sides : settings.segments_v) +
                          " cells",
                      "the mesh resolution");
  return model.tessellate(q, settings, std::move(name));
}

double curve_tube_radius(const Model& model, ConstVectorRef q) {
  check_coordinates(model, q);
  constexpr int kSegments = 64;
  if (const std::optional<Shape> shape = model.exact_shape(q);
      shape && std::holds_alternative<NurbsCurve>(*shape)) {
    return extent_radius(sample_curve(std::get<NurbsCurve>(*shape), kSegments));
  }
  return extent_radius(sampled_positions(model, q, model.parameter_domain(q), kSegments));
}

int minimum_segments(const ParameterDomain& domain, bool along_v) {
  const bool periodic = along_v ? domain.periodic_v : domain.periodic_u;
  const bool poles =
      along_v ? domain.pole_v_min && domain.pole_v_max : domain.pole_u_min && domain.pole_u_max;
  return periodic ? 3 : poles ? 2 : 1;
}

ParametricSurface sampled_model_surface(const Model& model, ConstVectorRef q,
                                        const ParameterDomain& domain,
                                        NormalOrientation orientation) {
  check_coordinates(model, q);
  if (model.parametric_dimension() != 2) {
    throw make_error("model tessellation: parametric dimension ", model.parametric_dimension(),
                     " is not a surface");
  }
  std::shared_ptr<const Model> copy = model.clone();
  Eigen::VectorXd coordinates = q;
  return ParametricSurface(
      domain,
      [copy, coordinates](double u, double v) {
        return copy->position(coordinates, Eigen::Vector2d(u, v));
      },
      {}, orientation);
}

TriangleMesh polyline_tube(const Eigen::MatrixX3d& points, bool closed, double radius, int sides,
                           std::string name) {
  const int segments =
      closed ? static_cast<int>(points.rows()) : static_cast<int>(points.rows()) - 1;
  return tessellate_curve_tube(polyline(points, closed), segments, radius, sides, std::move(name));
}

// The default of the contract (dynamics/core/model.h): surfaces through parametric_surface,
// curves as a tube around the exact curve or the sampled polyline.
TriangleMesh Model::tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                               std::string name) const {
  if (parametric_dimension() == 2) {
    const ParametricSurface surface = parametric_surface(q);
    if (settings.max_error > 0.0) {
      RestrictedMesh mesh(surface, settings.segments_u, settings.segments_v);
      mesh.refine(surface_error_criterion(surface, settings.max_error), settings.max_level);
      return mesh.to_triangle_mesh(std::move(name));
    }
    return tessellate_surface(surface, settings.segments_u, settings.segments_v, std::move(name));
  }
  const double radius =
      settings.tube_radius > 0.0 ? settings.tube_radius : curve_tube_radius(*this, q);
  if (const std::optional<Shape> shape = exact_shape(q);
      shape && std::holds_alternative<NurbsCurve>(*shape)) {
    return tessellate_curve_tube(std::get<NurbsCurve>(*shape), settings.segments_u, radius,
                                 settings.tube_sides, std::move(name));
  }
  const ParameterDomain domain = parameter_domain(q);
  const int segments = settings.segments_u;
  if (segments < (domain.periodic_u ? 3 : 1)) {
    throw make_error("model tessellation: curve resolution ", segments, " is below ",
                     domain.periodic_u ? 3 : 1);
  }
  return polyline_tube(sampled_positions(*this, q, domain, segments), domain.periodic_u, radius,
                       settings.tube_sides, std::move(name));
}

ParametricSurface Model::parametric_surface(ConstVectorRef q) const {
  return sampled_model_surface(*this, q, parameter_domain(q), normal_orientation());
}

}  // namespace dnurbs
