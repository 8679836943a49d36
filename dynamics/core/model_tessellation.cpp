#include "dynamics/core/model_tessellation.h"

#include <memory>
#include <utility>
#include <vector>

#include "dynamics/superquadric/deformable_superquadric_model.h"
#include "dynamics/dnurbs/dnurbs_curve.h"
#include "dynamics/dnurbs/dnurbs_surface.h"
#include "dynamics/grid/pde_surface.h"
#include "dynamics/grid/snake.h"
#include "dynamics/grid/terzopoulos_surface.h"
#include "core/error.h"
#include "surface/adaptive_tessellation.h"
#include "surface/parametric_surface_tessellation.h"
#include "surface/restricted_mesh.h"
#include "surface/tessellation.h"

namespace dnurbs {
namespace {

void check_coordinates(const Model& model, ConstVectorRef q) {
  if (q.size() != model.coordinate_count()) {
    throw make_error("model tessellation: q has ", q.size(), " entries, the model ",
                     model.coordinate_count());
  }
}

ParameterDomain grid_domain(const Grid& grid) {
  ParameterDomain domain;
  domain.u_max = (grid.nu() - 1) * grid.spacing();
  domain.v_max = (grid.nv() - 1) * grid.spacing();
  return domain;
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

double tube_radius(const ModelTessellationSettings& settings, const Eigen::MatrixX3d& samples) {
  if (settings.tube_radius > 0.0) {
    return settings.tube_radius;
  }
  const double extent = (samples.colwise().maxCoeff() - samples.colwise().minCoeff()).norm();
  return extent > 0.0 ? 0.01 * extent : 1e-3;
}

}  // namespace

ParameterDomain model_parameter_domain(const Model& model, ConstVectorRef q) {
  check_coordinates(model, q);
  if (const auto* nurbs = dynamic_cast<const DNurbsSurface*>(&model)) {
    return nurbs_parameter_domain(nurbs->surface(q));
  }
  if (dynamic_cast<const DeformableSuperquadricModel*>(&model) != nullptr) {
    return superquadric_parameter_domain();
  }
  if (const auto* grid = dynamic_cast<const TerzopoulosSurface*>(&model)) {
    return grid_domain(grid->grid());
  }
  if (const auto* grid = dynamic_cast<const PdeSurface*>(&model)) {
    return grid_domain(grid->grid());
  }
  throw make_error(
      "model tessellation: no known (u, v) domain for this model (parametric "
      "dimension ",
      model.parametric_dimension(), "); pass one explicitly");
}

NormalOrientation model_normal_orientation(const Model& model) {
  return dynamic_cast<const DeformableSuperquadricModel*>(&model) != nullptr
             ? NormalOrientation::kSvCrossSu
             : NormalOrientation::kSuCrossSv;
}

ParametricSurface model_surface(const Model& model, ConstVectorRef q) {
  check_coordinates(model, q);
  if (const auto* nurbs = dynamic_cast<const DNurbsSurface*>(&model)) {
    return parametric_surface(nurbs->surface(q));
  }
  return model_surface(model, q, model_parameter_domain(model, q), model_normal_orientation(model));
}

ParametricSurface model_surface(const Model& model, ConstVectorRef q, const ParameterDomain& domain,
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

TriangleMesh tessellate_model(const Model& model, ConstVectorRef q,
                              const ModelTessellationSettings& settings, std::string name) {
  check_coordinates(model, q);
  if (model.parametric_dimension() == 2) {
    const ParametricSurface surface = model_surface(model, q);
    if (settings.max_error > 0.0) {
      RestrictedMesh mesh(surface, settings.segments_u, settings.segments_v);
      mesh.refine(surface_error_criterion(surface, settings.max_error), settings.max_level);
      return mesh.to_triangle_mesh(std::move(name));
    }
    return tessellate_surface(surface, settings.segments_u, settings.segments_v, std::move(name));
  }
  if (const auto* curve = dynamic_cast<const DNurbsCurve*>(&model)) {
    const NurbsCurve shape = curve->curve(q);
    const double radius = tube_radius(settings, sample_curve(shape, settings.segments_u));
    return tessellate_curve_tube(shape, settings.segments_u, radius, settings.tube_sides,
                                 std::move(name));
  }
  if (const auto* snake = dynamic_cast<const Snake*>(&model)) {
    const bool closed = snake->chain().closed();
    const int segments = settings.segments_u;
    if (segments < (closed ? 3 : 1)) {
      throw make_error("model tessellation: curve resolution ", segments, " is below ",
                       closed ? 3 : 1);
    }
    Eigen::MatrixX3d points(closed ? segments : segments + 1, 3);
    for (int k = 0; k < points.rows(); ++k) {
      const double s = static_cast<double>(k) / segments;
      points.row(k) = model.position(q, Eigen::Vector2d(s, 0.0)).transpose();
    }
    return tessellate_curve_tube(polyline(points, closed), segments, tube_radius(settings, points),
                                 settings.tube_sides, std::move(name));
  }
  throw make_error(
      "model tessellation: no tessellation for this curve model (parametric "
      "dimension ",
      model.parametric_dimension(), ")");
}

}  // namespace dnurbs
