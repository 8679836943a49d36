#include "nurbs/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "core/error.h"

namespace dnurbs {
namespace {

constexpr int kSamplesPerSpan = 8;
constexpr int kNewtonSteps = 50;

// Sample parameters: kSamplesPerSpan per non-empty span of the domain.
std::vector<double> sample_parameters(const KnotVector& knots) {
  std::vector<double> samples;
  for (const int span : knots.non_empty_spans()) {
    for (int s = 0; s < kSamplesPerSpan; ++s) {
      samples.push_back(knots[span] + (knots[span + 1] - knots[span]) * s / kSamplesPerSpan);
    }
  }
  samples.push_back(knots.domain_end());
  return samples;
}

// Keeps a Newton iterate in the domain: periodic directions wrap, open ones clamp.
double keep_in_domain(const KnotVector& knots, double u) {
  if (knots.is_periodic()) {
    return knots.to_domain(u);
  }
  return std::clamp(u, knots.domain_start(), knots.domain_end());
}

void check_point(const Eigen::Vector3d& point) {
  if (!point.allFinite()) {
    throw make_error("closest point: query point (", point.x(), ", ", point.y(), ", ", point.z(),
                     ") is not finite");
  }
}

}  // namespace

CurveProjection closest_point(const NurbsCurve& curve, const Eigen::Vector3d& point) {
  check_point(point);
  const KnotVector& knots = curve.knots();
  double best = knots.domain_start();
  double best_distance = std::numeric_limits<double>::infinity();
  for (const double u : sample_parameters(knots)) {
    const double distance = (curve.point(u) - point).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = u;
    }
  }
  const double length = knots.domain_end() - knots.domain_start();
  double u = best;
  for (int step = 0; step < kNewtonSteps; ++step) {
    // f(u) = (C - P).C' = 0, f'(u) = |C'|^2 + (C - P).C''.
    const CurveDerivatives d = curve.derivatives(u, 2);
    const Eigen::Vector3d offset = d.row(0).transpose() - point;
    const Eigen::Vector3d first = d.row(1).transpose();
    const double slope = first.squaredNorm() + offset.dot(d.row(2).transpose());
    if (!(slope > 0.0)) {
      break;  // not locally convex: keep the best sample or iterate reached so far
    }
    const double next = keep_in_domain(knots, u - offset.dot(first) / slope);
    const double change = std::abs(next - u);
    u = next;
    if (change <= 1e-15 * length) {
      break;
    }
  }
  CurveProjection result;
  result.parameter = u;
  result.point = curve.point(u);
  result.distance = (result.point - point).norm();
  if (result.distance > std::sqrt(best_distance)) {  // Newton wandered off: keep the sample
    result.parameter = best;
    result.point = curve.point(best);
    result.distance = std::sqrt(best_distance);
  }
  return result;
}

namespace {

// Local minimisation of |S(u, v) - P|^2 from `start`: Newton steps on the gradient
// [(S - P).Su, (S - P).Sv] (Piegl & Tiller eq 6.6) where its Hessian is positive definite, the
// Gauss-Newton matrix [Su.Su, Su.Sv; Su.Sv, Sv.Sv] elsewhere, each step halved until the
// distance decreases.
Eigen::Vector2d minimise_distance(const NurbsSurface& surface, const Eigen::Vector3d& point,
                                  Eigen::Vector2d uv, double scale) {
  double distance = (surface.point(uv.x(), uv.y()) - point).squaredNorm();
  for (int step = 0; step < kNewtonSteps; ++step) {
    const SurfaceDerivatives d = surface.derivatives(uv.x(), uv.y(), 2);
    const Eigen::Vector3d offset = d(0, 0) - point;
    const Eigen::Vector2d gradient(offset.dot(d(1, 0)), offset.dot(d(0, 1)));
    Eigen::Matrix2d gauss_newton;
    gauss_newton << d(1, 0).squaredNorm(), d(1, 0).dot(d(0, 1)), d(1, 0).dot(d(0, 1)),
        d(0, 1).squaredNorm();
    Eigen::Matrix2d hessian = gauss_newton;
    hessian(0, 0) += offset.dot(d(2, 0));
    hessian(0, 1) += offset.dot(d(1, 1));
    hessian(1, 0) += offset.dot(d(1, 1));
    hessian(1, 1) += offset.dot(d(0, 2));
    Eigen::LDLT<Eigen::Matrix2d> solver(hessian);
    if (solver.info() != Eigen::Success || !solver.isPositive() ||
        solver.vectorD().minCoeff() <= 0.0) {
      solver.compute(gauss_newton + 1e-12 * gauss_newton.trace() * Eigen::Matrix2d::Identity());
    }
    const Eigen::Vector2d delta = solver.solve(gradient);
    if (!delta.allFinite()) {
      break;
    }
    double length = 1.0;
    bool improved = false;
    Eigen::Vector2d next = uv;
    for (int halving = 0; halving < 30 && !improved; ++halving, length *= 0.5) {
      next = Eigen::Vector2d(keep_in_domain(surface.knots_u(), uv.x() - length * delta.x()),
                             keep_in_domain(surface.knots_v(), uv.y() - length * delta.y()));
      const double next_distance = (surface.point(next.x(), next.y()) - point).squaredNorm();
      // Near the minimum the squared distance stalls at rounding level while Newton still
      // improves the parameters: accept steps that do not increase it beyond rounding.
      if (next_distance <= distance * (1.0 + 1e-14) + 1e-30) {
        improved = true;
        distance = next_distance;
      }
    }
    if (!improved) {
      break;
    }
    const double change = (next - uv).norm();
    uv = next;
    if (change <= 1e-15 * scale) {
      break;
    }
  }
  return uv;
}

}  // namespace

SurfaceProjection closest_point(const NurbsSurface& surface, const Eigen::Vector3d& point) {
  check_point(point);
  const std::vector<double> samples_u = sample_parameters(surface.knots_u());
  const std::vector<double> samples_v = sample_parameters(surface.knots_v());
  // The few nearest samples start local searches (a folded surface has several local minima).
  constexpr size_t kStarts = 4;
  std::vector<std::pair<double, Eigen::Vector2d>> nearest;
  for (const double u : samples_u) {
    for (const double v : samples_v) {
      nearest.emplace_back((surface.point(u, v) - point).squaredNorm(), Eigen::Vector2d(u, v));
    }
  }
  const size_t starts = std::min(kStarts, nearest.size());
  std::partial_sort(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(starts),
                    nearest.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const double scale = std::max(surface.knots_u().domain_end() - surface.knots_u().domain_start(),
                                surface.knots_v().domain_end() - surface.knots_v().domain_start());
  SurfaceProjection result;
  result.distance = std::numeric_limits<double>::infinity();
  for (size_t s = 0; s < starts; ++s) {
    const Eigen::Vector2d uv = minimise_distance(surface, point, nearest[s].second, scale);
    const Eigen::Vector3d on_surface = surface.point(uv.x(), uv.y());
    const double distance = (on_surface - point).norm();
    if (distance < result.distance) {
      result.parameter = uv;
      result.point = on_surface;
      result.distance = distance;
    }
  }
  return result;
}

}  // namespace dnurbs
