#include "dnurbs/nurbs/surface_projector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/bezier_extraction.h"

namespace dnurbs {
namespace {

// Boxes one query may halve in all its patches before the rest are settled by Newton's method
// from their centres: ~20 times what the hardest random surfaces of the tests need (a few
// hundred); reached when the stationary points form a curve (a query on an axis of revolution).
constexpr int kBoxBudget = 4000;

void check_query(const Eigen::Vector3d& point) {
  if (!point.allFinite()) {
    throw make_error("closest point: query point (", point.x(), ", ", point.y(), ", ", point.z(),
                     ") is not finite");
  }
}

// Knot values where the surface is only C^0 along `knots` (multiplicity >= degree) inside the
// domain, with the ends of an open direction (the boundary) or the seam of a periodic one if it
// is such a knot.
std::vector<double> edge_values(const KnotVector& knots) {
  std::vector<double> values;
  const double start = knots.domain_start();
  const double end = knots.domain_end();
  if (!knots.is_periodic()) {
    values.push_back(start);
  }
  for (int i = knots.degree(); i < knots.basis_count(); ++i) {
    const double knot = knots[i];
    const bool inside = knots.is_periodic() ? knot < end : knot > start && knot < end;
    if (inside && (values.empty() || knot != values.back()) &&
        knots.multiplicity(knot) >= knots.degree()) {
      values.push_back(knot);
    }
  }
  if (!knots.is_periodic()) {
    values.push_back(end);
  }
  return values;
}

}  // namespace

SurfaceProjector::SurfaceProjector(NurbsSurface surface) : surface_(std::move(surface)) {
  const Eigen::MatrixX3d& points = surface_.control_points();
  scale_ = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  const bool rational = surface_.is_rational();
  Eigen::MatrixXd homogeneous(points.rows(), 4);
  homogeneous.leftCols<3>() =
      rational ? Eigen::MatrixX3d(points.array().colwise() * surface_.weights().array()) : points;
  homogeneous.col(3) = rational ? surface_.weights() : Eigen::VectorXd::Ones(points.rows());
  const KnotVector& knots_u = surface_.knots_u();
  const KnotVector& knots_v = surface_.knots_v();
  for (const int span_u : knots_u.non_empty_spans()) {
    for (const int span_v : knots_v.non_empty_spans()) {
      patches_.emplace_back(bezier_patch(knots_u, knots_v, homogeneous, span_u, span_v),
                            knots_u.degree(), knots_v.degree(), rational,
                            Eigen::Vector4d(knots_u[span_u], knots_u[span_u + 1], knots_v[span_v],
                                            knots_v[span_v + 1]));
    }
  }
  add_edges(true, homogeneous);
  add_edges(false, homogeneous);
}

void SurfaceProjector::add_edges(bool fixed_u, const Eigen::MatrixXd& homogeneous) {
  const KnotVector& fixed = fixed_u ? surface_.knots_u() : surface_.knots_v();
  const KnotVector& along = fixed_u ? surface_.knots_v() : surface_.knots_u();
  const int count = along.control_point_count();
  for (const double value : edge_values(fixed)) {
    // The iso-parameter curve's homogeneous control points: sum_a N_a(value) H_(a, j).
    const int span = fixed.find_span(value);
    BasisValues basis;
    basis_functions(fixed, span, fixed.to_domain(value), basis);
    Eigen::MatrixX4d curve_rows = Eigen::MatrixX4d::Zero(count, 4);
    for (int a = 0; a <= fixed.degree(); ++a) {
      const int i = fixed.control_point_index(span, a);
      for (int j = 0; j < count; ++j) {
        const int index =
            fixed_u ? surface_.control_point_index(i, j) : surface_.control_point_index(j, i);
        curve_rows.row(j) += basis[a] * homogeneous.row(index);
      }
    }
    Eigen::MatrixX3d points =
        curve_rows.leftCols<3>().array().colwise() / curve_rows.col(3).array();
    NurbsCurve curve(along, std::move(points), curve_rows.col(3));
    edges_.push_back({CurveProjector(std::move(curve)), fixed_u, value});
  }
}

Eigen::Vector2d SurfaceProjector::to_parameter(const ProjectionPatch& patch, double s,
                                               double t) const {
  const Eigen::Vector4d& range = patch.range();
  Eigen::Vector2d parameter(s >= 1.0 ? range[1] : range[0] + s * (range[1] - range[0]),
                            t >= 1.0 ? range[3] : range[2] + t * (range[3] - range[2]));
  // A periodic direction reports its seam as the period start.
  if (surface_.knots_u().is_periodic() && parameter.x() >= surface_.knots_u().domain_end()) {
    parameter.x() = surface_.knots_u().domain_start();
  }
  if (surface_.knots_v().is_periodic() && parameter.y() >= surface_.knots_v().domain_end()) {
    parameter.y() = surface_.knots_v().domain_start();
  }
  return parameter;
}

/// Passes a patch's stationary points to the query's running answer as parameters (u, v).
class SurfaceProjector::PatchVisitor : public ProjectionVisitor {
 public:
  PatchVisitor(const SurfaceProjector& projector, const ProjectionPatch& patch,
               const Eigen::Vector3d& query, Best& best)
      : projector_(projector), patch_(patch), query_(query), best_(best) {}
  double stationary_point(double s, double t, bool exact) override {
    best_.offer((patch_.evaluate(s, t).point - query_).norm(),
                projector_.to_parameter(patch_, s, t), exact);
    return std::min(best_.bound, best_.distance);
  }
  double surface_point(double distance) override {
    best_.bound_by(distance);
    return std::min(best_.bound, best_.distance);
  }

 private:
  const SurfaceProjector& projector_;
  const ProjectionPatch& patch_;
  const Eigen::Vector3d& query_;
  Best& best_;
};

SurfaceProjection SurfaceProjector::closest_point(const Eigen::Vector3d& point) const {
  check_query(point);
  // Patches in the order of their lower bounds (box distances; ties by index).
  std::vector<std::pair<double, int>> order;
  order.reserve(patches_.size());
  for (size_t i = 0; i < patches_.size(); ++i) {
    order.emplace_back(patches_[i].lower_bound(point), static_cast<int>(i));
  }
  std::sort(order.begin(), order.end());
  Best best;
  best.absolute_tie = kProjectionTieTolerance * scale_;
  // A first bound from the nearest-looking patch's corners (points of the surface), then the
  // boundary and crease curves (their ends are the corners of the domain).
  const ProjectionPatch& first = patches_[static_cast<size_t>(order.front().second)];
  for (int corner = 0; corner < 4; ++corner) {
    best.bound_by((first.corner(corner) - point).norm());
  }
  for (const Edge& edge : edges_) {
    const std::optional<CurveProjection> nearest =
        edge.projector.closest_point_within(point, std::min(best.bound, best.distance));
    if (nearest) {
      best.offer(nearest->distance,
                 edge.fixed_u ? Eigen::Vector2d(edge.value, nearest->parameter)
                              : Eigen::Vector2d(nearest->parameter, edge.value),
                 true);
    }
  }
  // Interior stationary points of every patch that may hold a nearer point.
  thread_local std::vector<double> workspace;
  int budget = kBoxBudget;
  for (const auto& [lower, index] : order) {
    if (lower > best.pruning_bound()) {
      break;
    }
    const ProjectionPatch& patch = patches_[static_cast<size_t>(index)];
    PatchVisitor visitor(*this, patch, point, best);
    patch.stationary_points(point, std::min(best.bound, best.distance), best.absolute_tie,
                            workspace, budget, visitor);
  }
  SurfaceProjection result;
  result.parameter = best.parameter;
  result.point = surface_.point(best.parameter.x(), best.parameter.y());
  result.distance = (result.point - point).norm();
  return result;
}

Eigen::Vector2d SurfaceProjector::invert(const Eigen::Vector3d& point, double tolerance) const {
  const SurfaceProjection projection = closest_point(point);
  if (!(projection.distance <= tolerance)) {
    throw make_error("point (", point.x(), ", ", point.y(), ", ", point.z(), ") is ",
                     projection.distance, " from the surface, farther than the tolerance ",
                     tolerance);
  }
  return projection.parameter;
}

}  // namespace dnurbs
