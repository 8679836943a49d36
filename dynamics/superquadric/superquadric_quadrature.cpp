#include "dnurbs/dynamics/superquadric/superquadric_quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {
namespace {

/// A 1-D rule on [a, b] graded with exponent p toward the singular ends (Terzopoulos 2003, eq. 1.38
/// integrands with the |cos w|^e singularities of the signed powers): x = a + (b - a) g(tau),
/// g = tau^p (singular at a), 1 - (1 - tau)^p (at b), tau^p / (tau^p + (1 - tau)^p) (both).
void graded_rule(const GaussLegendreRule& rule, double a, double b, bool singular_a,
                 bool singular_b, double p, std::vector<double>& nodes,
                 std::vector<double>& weights) {
  const auto n = static_cast<size_t>(rule.nodes.size());
  nodes.resize(n);
  weights.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const double tau = 0.5 * (rule.nodes[static_cast<Eigen::Index>(k)] + 1.0);
    const double w = 0.5 * rule.weights[static_cast<Eigen::Index>(k)];
    double g = tau;
    double dg = 1.0;
    if (singular_a && singular_b) {
      const double left = std::pow(tau, p);
      const double right = std::pow(1.0 - tau, p);
      g = left / (left + right);
      dg = p * std::pow(tau, p - 1.0) * std::pow(1.0 - tau, p - 1.0) /
           ((left + right) * (left + right));
    } else if (singular_a) {
      g = std::pow(tau, p);
      dg = p * std::pow(tau, p - 1.0);
    } else if (singular_b) {
      g = 1.0 - std::pow(1.0 - tau, p);
      dg = p * std::pow(1.0 - tau, p - 1.0);
    }
    nodes[k] = a + (b - a) * g;
    weights[k] = (b - a) * dg * w;
  }
}

/// True if w is a multiple of pi/2 (to 1e-12).
bool at_quarter_turn(double w) {
  const double turns = w / (0.5 * std::numbers::pi);
  return std::abs(turns - std::round(turns)) < 1e-12;
}

}  // namespace

std::vector<ParameterQuadraturePoint> superquadric_quadrature_points(
    const ParametricFeMesh& mesh, const SuperquadricShapeParameters& shape,
    int points_per_direction, bool graded) {
  const double e1 = shape[SuperquadricShapeParameter::kSquareness1];
  const double e2 = shape[SuperquadricShapeParameter::kSquareness2];
  if (!graded || (e1 >= 1.0 && e2 >= 1.0)) {
    return mesh.quadrature_points(points_per_direction);
  }
  const GaussLegendreRule& rule = gauss_legendre_rule(points_per_direction);
  const double p_u = std::max(1.0, 1.0 / e1);
  const double p_v = std::max(1.0, 1.0 / e2);
  const bool grade_u = p_u > 1.0;
  const bool grade_v = p_v > 1.0;
  std::vector<ParameterQuadraturePoint> points;
  std::vector<double> nodes_u, weights_u, nodes_v, weights_v;
  for (int i = 0; i < mesh.cells_u(); ++i) {
    for (int j = 0; j < mesh.cells_v(); ++j) {
      const Eigen::Vector4d box = mesh.cell_bounds(i, j);
      graded_rule(rule, box[0], box[1], grade_u && at_quarter_turn(box[0]),
                  grade_u && at_quarter_turn(box[1]), p_u, nodes_u, weights_u);
      graded_rule(rule, box[2], box[3], grade_v && at_quarter_turn(box[2]),
                  grade_v && at_quarter_turn(box[3]), p_v, nodes_v, weights_v);
      for (size_t a = 0; a < nodes_u.size(); ++a) {
        for (size_t b = 0; b < nodes_v.size(); ++b) {
          points.push_back({nodes_u[a], nodes_v[b], weights_u[a] * weights_v[b], i, j});
        }
      }
    }
  }
  return points;
}

}  // namespace dnurbs
