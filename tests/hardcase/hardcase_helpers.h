#pragma once
// Shared pieces of the hard-case tests: D-NURBS shapes at rest, perturbed states, the energy of
// a linear model about its rest shape, and the RESULTS.md record of each case.

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"
#include "dnurbs/nurbs/shape_generators.h"

namespace dnurbs::hardcase {

/// "%.3g" of a number, the format of the RESULTS.md table.
inline std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

/// Records the headline number of a case for the RESULTS.md table (gtest XML properties).
inline void record_result(const std::string& measure, double value, const std::string& bound) {
  ::testing::Test::RecordProperty("measure", measure);
  ::testing::Test::RecordProperty("value", format_number(value));
  ::testing::Test::RecordProperty("bound", bound);
}

/// Greville abscissae of a knot vector: control points there make x(u) = u.
inline Eigen::VectorXd greville(const KnotVector& knots) {
  const std::vector<double> abscissae = greville_abscissae(knots);
  return Eigen::Map<const Eigen::VectorXd>(abscissae.data(),
                                           static_cast<Eigen::Index>(abscissae.size()));
}

/// The straight cubic x(u) = (u, 0, 0) on [0, 1] with `spans` uniform spans: the rest shape of
/// both tension and rigidity (x_uu = 0).
inline NurbsCurve straight_cubic(int spans) {
  const KnotVector knots = KnotVector::clamped_uniform(3, spans + 3);
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(knots.control_point_count(), 3);
  points.col(0) = greville(knots);
  return NurbsCurve(knots, points);
}

/// The flat bicubic patch (u, v, 0) on [0, 1]^2 with `spans` uniform spans per direction.
inline NurbsSurface flat_bicubic(int spans) {
  const KnotVector knots = KnotVector::clamped_uniform(3, spans + 3);
  const Eigen::VectorXd g = greville(knots);
  const auto n = g.size();
  Eigen::MatrixX3d points(n * n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      points.row(i * n + j) << g[i], g[j], 0.0;
    }
  }
  return NurbsSurface(knots, knots, points);
}

/// A deterministic pseudo-random vector in [-1, 1]^n.
inline Eigen::VectorXd pattern_vector(Eigen::Index n, double seed) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    v[i] = std::sin(12.9898 * static_cast<double>(i + 1) + seed * 78.233);
  }
  return v;
}

/// Total energy (1/2) qd^T M qd + E(q) of a one-model system with constant matrices.
inline double total_energy(const System& system) {
  return system.kinetic_energy() + system.potential_energy();
}

}  // namespace dnurbs::hardcase
