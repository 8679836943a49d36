#include "dnurbs/nurbs/periodic_form.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

/// Relative tolerance of the repeated control points and weights of an open form (they are
/// copies, so only a format's decimal round trip can separate them).
constexpr double kRepeatTolerance = 1e-12;

/// The periodic knot vector whose extension the open vector `knots` is, if it is one.
std::optional<KnotVector> periodic_basis_of(const KnotVector& knots) {
  const int p = knots.degree();
  const int n = knots.control_point_count() - p;
  if (knots.is_periodic() || n < p + 1) {
    return std::nullopt;
  }
  const std::vector<double>& t = knots.knots();
  const double period = knots[p + n] - knots[p];
  if (!(period > 0.0)) {
    return std::nullopt;
  }
  for (int i = 0; i + n < knots.size(); ++i) {
    const double scale = std::max(
        {std::abs(t[static_cast<size_t>(i)]), std::abs(t[static_cast<size_t>(i + n)]), period});
    if (std::abs(t[static_cast<size_t>(i + n)] - t[static_cast<size_t>(i)] - period) >
        kPeriodicSeamTolerance * scale) {
      return std::nullopt;
    }
  }
  try {
    return KnotVector::periodic(p, std::vector<double>(t.begin() + p, t.begin() + p + n + 1));
  } catch (const Error&) {
    return std::nullopt;  // a multiplicity above p across the seam: no periodic basis
  }
}

double largest_magnitude(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights) {
  return std::max(points.cwiseAbs().maxCoeff(), weights.cwiseAbs().maxCoeff());
}

bool repeats(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights, int first, int copy,
             double scale) {
  return (points.row(first) - points.row(copy)).cwiseAbs().maxCoeff() <= kRepeatTolerance * scale &&
         std::abs(weights(first) - weights(copy)) <= kRepeatTolerance * scale;
}

/// Extended (open) control point rows of a periodic direction: row k of the result is distinct
/// row k mod n.
std::vector<int> wrapped_indices(const KnotVector& knots) {
  const int n = knots.control_point_count();
  const int count = knots.is_periodic() ? n + knots.degree() : n;
  std::vector<int> indices(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) {
    indices[static_cast<size_t>(k)] = k % n;
  }
  return indices;
}

KnotVector open_basis(const KnotVector& knots) {
  return knots.is_periodic() ? KnotVector(knots.degree(), knots.knots()) : knots;
}

}  // namespace

NurbsCurve open_form(const NurbsCurve& curve) {
  if (!curve.is_periodic()) {
    return curve;
  }
  const std::vector<int> rows = wrapped_indices(curve.knots());
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(rows.size()), 3);
  Eigen::VectorXd weights(static_cast<Eigen::Index>(rows.size()));
  for (size_t k = 0; k < rows.size(); ++k) {
    points.row(static_cast<Eigen::Index>(k)) = curve.control_points().row(rows[k]);
    weights(static_cast<Eigen::Index>(k)) = curve.weights()(rows[k]);
  }
  return {open_basis(curve.knots()), points, weights};
}

NurbsSurface open_form(const NurbsSurface& surface) {
  if (!surface.knots_u().is_periodic() && !surface.knots_v().is_periodic()) {
    return surface;
  }
  const std::vector<int> rows_u = wrapped_indices(surface.knots_u());
  const std::vector<int> rows_v = wrapped_indices(surface.knots_v());
  const auto count = static_cast<Eigen::Index>(rows_u.size() * rows_v.size());
  Eigen::MatrixX3d points(count, 3);
  Eigen::VectorXd weights(count);
  Eigen::Index row = 0;
  for (const int i : rows_u) {
    for (const int j : rows_v) {
      const int source = surface.control_point_index(i, j);
      points.row(row) = surface.control_points().row(source);
      weights(row++) = surface.weights()(source);
    }
  }
  return {open_basis(surface.knots_u()), open_basis(surface.knots_v()), points, weights};
}

Shape open_form(const Shape& shape) {
  return std::visit([](const auto& value) { return Shape(open_form(value)); }, shape);
}

NurbsCurve periodic_form(const NurbsCurve& curve) {
  const std::optional<KnotVector> basis = periodic_basis_of(curve.knots());
  if (!basis) {
    return curve;
  }
  const int n = basis->control_point_count();
  const double scale = largest_magnitude(curve.control_points(), curve.weights());
  for (int k = 0; k < curve.degree(); ++k) {
    if (!repeats(curve.control_points(), curve.weights(), k, n + k, scale)) {
      return curve;
    }
  }
  return {*basis, curve.control_points().topRows(n), curve.weights().head(n)};
}

NurbsSurface periodic_form(const NurbsSurface& surface) {
  const double scale = largest_magnitude(surface.control_points(), surface.weights());
  const int count_u = surface.control_point_count_u();
  const int count_v = surface.control_point_count_v();
  // Direction u: rows i and n_u + i (for every j); direction v: columns j and n_v + j.
  std::optional<KnotVector> basis_u = periodic_basis_of(surface.knots_u());
  for (int k = 0; basis_u && k < surface.degree_u(); ++k) {
    for (int j = 0; basis_u && j < count_v; ++j) {
      if (!repeats(surface.control_points(), surface.weights(), surface.control_point_index(k, j),
                   surface.control_point_index(basis_u->control_point_count() + k, j), scale)) {
        basis_u.reset();
      }
    }
  }
  std::optional<KnotVector> basis_v = periodic_basis_of(surface.knots_v());
  for (int k = 0; basis_v && k < surface.degree_v(); ++k) {
    for (int i = 0; basis_v && i < count_u; ++i) {
      if (!repeats(surface.control_points(), surface.weights(), surface.control_point_index(i, k),
                   surface.control_point_index(i, basis_v->control_point_count() + k), scale)) {
        basis_v.reset();
      }
    }
  }
  if (!basis_u && !basis_v) {
    return surface;
  }
  const KnotVector knots_u = basis_u ? *basis_u : surface.knots_u();
  const KnotVector knots_v = basis_v ? *basis_v : surface.knots_v();
  const int kept_u = knots_u.control_point_count();
  const int kept_v = knots_v.control_point_count();
  Eigen::MatrixX3d points(kept_u * kept_v, 3);
  Eigen::VectorXd weights(kept_u * kept_v);
  for (int i = 0; i < kept_u; ++i) {
    for (int j = 0; j < kept_v; ++j) {
      const int source = surface.control_point_index(i, j);
      points.row(i * kept_v + j) = surface.control_points().row(source);
      weights(i * kept_v + j) = surface.weights()(source);
    }
  }
  return {knots_u, knots_v, points, weights};
}

}  // namespace dnurbs
