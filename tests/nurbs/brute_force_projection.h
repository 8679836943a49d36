#pragma once
// Brute-force references for the closest-point tests, independent of the projectors: dense
// sampling of the shape, Newton's method from every sample that is a discrete local minimum of
// the distance (and from the ends, the boundary curves, the corners and the C^0 creases), the
// best result kept. It uses only NurbsCurve / NurbsSurface evaluation.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::testing {

/// Parameters every 1/samples of each non-empty span (and the domain end).
inline std::vector<double> dense_parameters(const KnotVector& knots, int samples) {
  std::vector<double> parameters;
  for (const int span : knots.non_empty_spans()) {
    for (int s = 0; s < samples; ++s) {
      parameters.push_back(knots[span] + (knots[span + 1] - knots[span]) * s / samples);
    }
  }
  parameters.push_back(knots.domain_end());
  return parameters;
}

/// Newton's method on (C - Q).C' = 0 from u, kept in [low, high]; returns the distance reached
/// and updates u.
inline double refine_on_curve(const NurbsCurve& curve, const Eigen::Vector3d& query, double& u,
                              double low, double high) {
  for (int step = 0; step < 60; ++step) {
    const CurveDerivatives d = curve.derivatives(u, 2);
    const Eigen::Vector3d offset = d.row(0).transpose() - query;
    const double slope = d.row(1).squaredNorm() + offset.dot(d.row(2).transpose());
    const double gradient = offset.dot(d.row(1).transpose());
    if (!(slope > 0.0)) {
      break;
    }
    const double next = std::clamp(u - gradient / slope, low, high);
    const bool done = std::abs(next - u) <= 1e-16 * (1.0 + std::abs(u));
    u = next;
    if (done) {
      break;
    }
  }
  return (curve.point(u) - query).norm();
}

/// Sample distances of a curve, kept between queries (the sampling is the expensive part).
struct CurveSamples {
  std::vector<double> parameters;
  std::vector<Eigen::Vector3d> points;
};

/// Samples every 1/samples_per_span of each span, then halves every interval whose polyline
/// (through its midpoint) is longer than 1/500 of the control net's size (to 2^-16 of the
/// span): dense in arc length too, where extreme weights crowd a curve's turns into a sliver of
/// parameter.
inline CurveSamples sample_curve(const NurbsCurve& curve, int samples_per_span) {
  const Eigen::MatrixX3d& net = curve.control_points();
  const double step = (net.colwise().maxCoeff() - net.colwise().minCoeff()).norm() / 500.0;
  CurveSamples result;
  const std::vector<double> coarse = dense_parameters(curve.knots(), samples_per_span);
  const auto refine = [&](const auto& self, double a, const Eigen::Vector3d& pa, double b,
                          const Eigen::Vector3d& pb, int depth) -> void {
    const double middle = 0.5 * (a + b);
    const Eigen::Vector3d pm = curve.point(middle);
    if (depth < 16 && (pm - pa).norm() + (pb - pm).norm() > step) {
      self(self, a, pa, middle, pm, depth + 1);
      self(self, middle, pm, b, pb, depth + 1);
      return;
    }
    result.parameters.push_back(middle);
    result.points.push_back(pm);
    result.parameters.push_back(b);
    result.points.push_back(pb);
  };
  result.parameters.push_back(coarse.front());
  result.points.push_back(curve.point(coarse.front()));
  for (size_t i = 0; i + 1 < coarse.size(); ++i) {
    refine(refine, coarse[i], result.points.back(), coarse[i + 1], curve.point(coarse[i + 1]), 0);
  }
  return result;
}

/// The nearest distance to the curve: Newton from every discrete local minimum of the sampled
/// distance (the ends of an open curve always among them).
inline double brute_force_distance(const NurbsCurve& curve, const CurveSamples& samples,
                                   const Eigen::Vector3d& query) {
  const std::vector<double>& u = samples.parameters;
  const int count = static_cast<int>(u.size());
  std::vector<double> distance(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    distance[static_cast<size_t>(i)] = (samples.points[static_cast<size_t>(i)] - query).norm();
  }
  const bool periodic = curve.is_periodic();
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    // Neighbors: a periodic curve's last sample is its first (the seam).
    const int previous = i > 0 ? i - 1 : (periodic ? count - 2 : i);
    const int next = i + 1 < count ? i + 1 : (periodic ? 1 : i);
    const double here = distance[static_cast<size_t>(i)];
    best = std::min(best, here);
    if (here <= distance[static_cast<size_t>(previous)] &&
        here <= distance[static_cast<size_t>(next)]) {
      double parameter = u[static_cast<size_t>(i)];
      const double low = i > 0 ? u[static_cast<size_t>(i - 1)] : u.front();
      const double high = i + 1 < count ? u[static_cast<size_t>(i + 1)] : u.back();
      best = std::min(best, refine_on_curve(curve, query, parameter, low, high));
    }
  }
  return best;
}

/// Sampled surface with its iso-curves at the domain boundary and at C^0 creases.
struct SurfaceSamples {
  std::vector<double> u;
  std::vector<double> v;
  std::vector<Eigen::Vector3d> points;  ///< u index outer
  std::vector<NurbsCurve> edges;
  std::vector<CurveSamples> edge_samples;
};

/// The iso-curve u = value (fixed_u) or v = value of a surface, exactly: the curve along the
/// other direction whose homogeneous control points are sum_a N_a(value) (w P, w).
inline NurbsCurve iso_curve(const NurbsSurface& surface, bool fixed_u, double value) {
  const KnotVector& fixed = fixed_u ? surface.knots_u() : surface.knots_v();
  const KnotVector& along = fixed_u ? surface.knots_v() : surface.knots_u();
  const int span = fixed.find_span(value);
  BasisValues basis;
  basis_functions(fixed, span, fixed.to_domain(value), basis);
  const int count = along.control_point_count();
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(count, 3);
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(count);
  for (int a = 0; a <= fixed.degree(); ++a) {
    const int i = fixed.control_point_index(span, a);
    for (int j = 0; j < count; ++j) {
      const int index =
          fixed_u ? surface.control_point_index(i, j) : surface.control_point_index(j, i);
      const double w = basis[a] * surface.weights()[index];
      points.row(j) += w * surface.control_points().row(index);
      weights[j] += w;
    }
  }
  points.array().colwise() /= weights.array();
  return {along, points, weights};
}

/// Grid parameters along u (along_u) or v: per non-empty span at least `minimum` samples, more
/// where the iso-curves at 9 parameters across run longer than 1/100 of the control net's size
/// between samples (up to 128 per span), so that the grid is dense in space, not only in
/// parameters.
inline std::vector<double> adaptive_parameters(const NurbsSurface& surface, bool along_u,
                                               int minimum) {
  const KnotVector& knots = along_u ? surface.knots_u() : surface.knots_v();
  const KnotVector& across = along_u ? surface.knots_v() : surface.knots_u();
  const Eigen::MatrixX3d& net = surface.control_points();
  const double step = (net.colwise().maxCoeff() - net.colwise().minCoeff()).norm() / 100.0;
  const auto point = [&](double a, double b) {
    return along_u ? surface.point(a, b) : surface.point(b, a);
  };
  std::vector<double> parameters;
  for (const int span : knots.non_empty_spans()) {
    const double start = knots[span];
    const double end = knots[span + 1];
    double longest = 0.0;  // longest iso-curve polyline over the span (64 pieces)
    for (int c = 0; c <= 8; ++c) {
      const double b =
          across.domain_start() + (across.domain_end() - across.domain_start()) * c / 8;
      double length = 0.0;
      for (int i = 0; i < 64; ++i) {
        length += (point(start + (end - start) * (i + 1) / 64, b) -
                   point(start + (end - start) * i / 64, b))
                      .norm();
      }
      longest = std::max(longest, length);
    }
    const int count = std::clamp(static_cast<int>(std::ceil(longest / step)), minimum, 128);
    for (int i = 0; i < count; ++i) {
      parameters.push_back(start + (end - start) * i / count);
    }
  }
  parameters.push_back(knots.domain_end());
  return parameters;
}

inline SurfaceSamples sample_surface(const NurbsSurface& surface, int samples_per_span) {
  SurfaceSamples result;
  result.u = adaptive_parameters(surface, true, samples_per_span);
  result.v = adaptive_parameters(surface, false, samples_per_span);
  for (const double u : result.u) {
    for (const double v : result.v) {
      result.points.push_back(surface.point(u, v));
    }
  }
  for (const bool fixed_u : {true, false}) {
    const KnotVector& knots = fixed_u ? surface.knots_u() : surface.knots_v();
    std::vector<double> values;
    if (!knots.is_periodic()) {
      values = {knots.domain_start(), knots.domain_end()};
    }
    for (const double knot : knots.knots()) {
      if (knot >= knots.domain_start() && knot < knots.domain_end() &&
          knots.multiplicity(knot) >= knots.degree() &&
          std::find(values.begin(), values.end(), knot) == values.end()) {
        values.push_back(knot);
      }
    }
    for (const double value : values) {
      result.edges.push_back(iso_curve(surface, fixed_u, value));
      result.edge_samples.push_back(sample_curve(result.edges.back(), 4 * samples_per_span));
    }
  }
  return result;
}

/// Damped Newton on the gradient of |S - Q|^2 / 2 from (u, v) (periodic directions wrap, open
/// ones are clamped to the domain); steps that do not decrease the distance are halved.
inline double refine_on_surface(const NurbsSurface& surface, const Eigen::Vector3d& query,
                                Eigen::Vector2d uv) {
  const KnotVector& knots_u = surface.knots_u();
  const KnotVector& knots_v = surface.knots_v();
  const auto keep = [](const KnotVector& knots, double x) {
    return knots.is_periodic() ? knots.to_domain(x)
                               : std::clamp(x, knots.domain_start(), knots.domain_end());
  };
  double best = (surface.point(uv.x(), uv.y()) - query).norm();
  for (int step = 0; step < 60; ++step) {
    const SurfaceDerivatives d = surface.derivatives(uv.x(), uv.y(), 2);
    const Eigen::Vector3d offset = d(0, 0) - query;
    const Eigen::Vector2d gradient(offset.dot(d(1, 0)), offset.dot(d(0, 1)));
    Eigen::Matrix2d hessian;
    hessian << d(1, 0).squaredNorm() + offset.dot(d(2, 0)),
        d(1, 0).dot(d(0, 1)) + offset.dot(d(1, 1)), d(1, 0).dot(d(0, 1)) + offset.dot(d(1, 1)),
        d(0, 1).squaredNorm() + offset.dot(d(0, 2));
    Eigen::Vector2d delta = -hessian.inverse() * gradient;
    if (!delta.allFinite() || gradient.dot(delta) >= 0.0) {
      delta = -gradient / (d(1, 0).squaredNorm() + d(0, 1).squaredNorm());  // steepest descent
    }
    bool improved = false;
    Eigen::Vector2d next = uv;
    for (int halving = 0; halving < 40 && !improved; ++halving, delta *= 0.5) {
      next = Eigen::Vector2d(keep(knots_u, uv.x() + delta.x()), keep(knots_v, uv.y() + delta.y()));
      const double distance = (surface.point(next.x(), next.y()) - query).norm();
      if (distance <= best) {
        improved = true;
        best = distance;
      }
    }
    if (!improved || (next - uv).cwiseAbs().maxCoeff() <= 1e-16) {
      break;
    }
    uv = next;
  }
  return best;
}

/// The nearest distance to the surface: Newton from every discrete local minimum of the sampled
/// grid (8 neighbors, wrapping across periodic seams), and the brute-force distance to every
/// boundary and crease curve (whose ends are the corners).
inline double brute_force_distance(const NurbsSurface& surface, const SurfaceSamples& samples,
                                   const Eigen::Vector3d& query) {
  const int count_u = static_cast<int>(samples.u.size());
  const int count_v = static_cast<int>(samples.v.size());
  std::vector<double> distance(samples.points.size());
  for (size_t i = 0; i < samples.points.size(); ++i) {
    distance[i] = (samples.points[i] - query).norm();
  }
  const auto neighbor = [](int i, int step, int count, bool periodic) {
    const int j = i + step;
    if (j >= 0 && j < count) {
      return j;
    }
    return periodic ? (j < 0 ? count - 2 : 1) : i;
  };
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      const double here = distance[static_cast<size_t>(i * count_v + j)];
      best = std::min(best, here);
      bool minimum = true;
      for (int di = -1; di <= 1 && minimum; ++di) {
        for (int dj = -1; dj <= 1 && minimum; ++dj) {
          const int a = neighbor(i, di, count_u, surface.knots_u().is_periodic());
          const int b = neighbor(j, dj, count_v, surface.knots_v().is_periodic());
          minimum = here <= distance[static_cast<size_t>(a * count_v + b)];
        }
      }
      if (minimum) {
        best =
            std::min(best, refine_on_surface(surface, query,
                                             Eigen::Vector2d(samples.u[static_cast<size_t>(i)],
                                                             samples.v[static_cast<size_t>(j)])));
      }
    }
  }
  for (size_t e = 0; e < samples.edges.size(); ++e) {
    best = std::min(best, brute_force_distance(samples.edges[e], samples.edge_samples[e], query));
  }
  return best;
}

}  // namespace dnurbs::testing
