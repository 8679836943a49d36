#include "dnurbs/surface/parametric_fe_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {
namespace {

constexpr double kPi = std::numbers::pi;
/// How far outside [-pi/2, pi/2] a u may lie (rounding of a caller's arithmetic) before it is
/// rejected; within it u is clamped.
constexpr double kDomainSlack = 1e-12;

/// Which scalar integrand a matrix assembles.
struct Integrand {
  double membrane_u = 0.0;
  double membrane_v = 0.0;
  double mass = 0.0;
};

}  // namespace

ParametricFeMesh::ParametricFeMesh(int cells_u, int cells_v)
    : cells_u_(cells_u), cells_v_(cells_v) {
  if (cells_u < 2) {
    throw make_error("parametric FE mesh: cells_u is ", cells_u, "; it must be at least 2");
  }
  if (cells_v < 3) {
    throw make_error("parametric FE mesh: cells_v is ", cells_v, "; it must be at least 3");
  }
  step_u_ = kPi / cells_u;
  step_v_ = 2.0 * kPi / cells_v;
}

int ParametricFeMesh::node_index(int row, int column) const {
  if (row < 0 || row > cells_u_) {
    throw make_error("parametric FE mesh: row ", row, " is outside 0..", cells_u_);
  }
  if (row == 0) {
    return south_pole_node();
  }
  if (row == cells_u_) {
    return north_pole_node();
  }
  const int wrapped = ((column % cells_v_) + cells_v_) % cells_v_;
  return 1 + (row - 1) * cells_v_ + wrapped;
}

Eigen::Vector2d ParametricFeMesh::node_parameter(int node) const {
  if (node < 0 || node >= node_count()) {
    throw make_error("parametric FE mesh: node ", node, " is outside 0..", node_count() - 1);
  }
  if (node == south_pole_node()) {
    return {-kPi / 2, 0.0};
  }
  if (node == north_pole_node()) {
    return {kPi / 2, 0.0};
  }
  const int row = 1 + (node - 1) / cells_v_;
  const int column = (node - 1) % cells_v_;
  return {-kPi / 2 + row * step_u_, -kPi + column * step_v_};
}

Eigen::Vector4d ParametricFeMesh::cell_bounds(int cell_u, int cell_v) const {
  if (cell_u < 0 || cell_u >= cells_u_ || cell_v < 0 || cell_v >= cells_v_) {
    throw make_error("parametric FE mesh: cell (", cell_u, ", ", cell_v, ") is outside 0..",
                     cells_u_ - 1, " x 0..", cells_v_ - 1);
  }
  return {-kPi / 2 + cell_u * step_u_, -kPi / 2 + (cell_u + 1) * step_u_, -kPi + cell_v * step_v_,
          -kPi + (cell_v + 1) * step_v_};
}

FeShapeValues ParametricFeMesh::shape_values(double u, double v) const {
  if (!std::isfinite(u) || u < -kPi / 2 - kDomainSlack || u > kPi / 2 + kDomainSlack) {
    throw make_error("parametric FE mesh: u = ", u, " is outside [-pi/2, pi/2]");
  }
  if (!std::isfinite(v)) {
    throw make_error("parametric FE mesh: v = ", v, " is not finite");
  }
  // Locate the cell and the local coordinates (xi, eta) in [0, 1]^2.
  const double s = std::clamp((u + kPi / 2) / step_u_, 0.0, static_cast<double>(cells_u_));
  const int row = std::min(static_cast<int>(std::floor(s)), cells_u_ - 1);
  const double xi = s - row;
  double wrapped = std::fmod(v + kPi, 2.0 * kPi);  // v + pi wrapped into [0, 2 pi)
  if (wrapped < 0.0) {
    wrapped += 2.0 * kPi;
  }
  const double t = wrapped / step_v_;
  int column = static_cast<int>(std::floor(t));
  const double eta = t - column;
  if (column >= cells_v_) {
    column -= cells_v_;  // wrapped rounded up to 2 pi: the seam column
  }

  // Bilinear corner functions; corners on a pole row are one node and add up.
  const double n_xi[2] = {1.0 - xi, xi};
  const double n_eta[2] = {1.0 - eta, eta};
  const double dn_xi[2] = {-1.0 / step_u_, 1.0 / step_u_};
  const double dn_eta[2] = {-1.0 / step_v_, 1.0 / step_v_};
  FeShapeValues shape;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      const int node = node_index(row + a, column + b);
      int slot = 0;
      while (slot < shape.active_count && shape.node[slot] != node) {
        ++slot;
      }
      if (slot == shape.active_count) {
        shape.node[slot] = node;
        ++shape.active_count;
      }
      shape.value[slot] += n_xi[a] * n_eta[b];
      shape.d_u[slot] += dn_xi[a] * n_eta[b];
      shape.d_v[slot] += n_xi[a] * dn_eta[b];
    }
  }
  return shape;
}

FeDisplacement ParametricFeMesh::displacement(const Eigen::Ref<const Eigen::VectorXd>& q_d,
                                              const FeShapeValues& shape) const {
  FeDisplacement result;
  result.value.setZero();
  result.d_u.setZero();
  result.d_v.setZero();
  for (int a = 0; a < shape.active_count; ++a) {
    const Eigen::Vector3d nodal = q_d.segment<3>(3 * static_cast<Eigen::Index>(shape.node[a]));
    result.value += shape.value[a] * nodal;
    result.d_u += shape.d_u[a] * nodal;
    result.d_v += shape.d_v[a] * nodal;
  }
  return result;
}

Eigen::SparseMatrix<double> ParametricFeMesh::shape_matrix(double u, double v) const {
  const FeShapeValues shape = shape_values(u, v);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(3) * FeShapeValues::kMaxActive);
  for (int a = 0; a < shape.active_count; ++a) {
    for (int k = 0; k < 3; ++k) {
      entries.emplace_back(k, 3 * shape.node[a] + k, shape.value[a]);
    }
  }
  Eigen::SparseMatrix<double> matrix(3, coordinate_count());
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

namespace {

/// Assembles integral (cu N_a,u N_b,u + cv N_a,v N_b,v + cm N_a N_b) du dv cell by cell.
Eigen::SparseMatrix<double> assemble_scalar(const ParametricFeMesh& mesh, const Integrand& f,
                                            int points_per_direction) {
  const GaussLegendreRule& rule = gauss_legendre_rule(points_per_direction);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(mesh.cells_u()) * mesh.cells_v() * 16);
  for (int i = 0; i < mesh.cells_u(); ++i) {
    for (int j = 0; j < mesh.cells_v(); ++j) {
      const Eigen::Vector4d box = mesh.cell_bounds(i, j);
      const double half_u = 0.5 * (box[1] - box[0]);
      const double half_v = 0.5 * (box[3] - box[2]);
      // Element matrix by tensor Gauss-Legendre quadrature mapped onto the cell.
      Eigen::Matrix4d element = Eigen::Matrix4d::Zero();
      FeShapeValues shape;
      for (int p = 0; p < points_per_direction; ++p) {
        const double u = box[0] + half_u * (rule.nodes[p] + 1.0);
        for (int r = 0; r < points_per_direction; ++r) {
          const double v = box[2] + half_v * (rule.nodes[r] + 1.0);
          const double weight = rule.weights[p] * rule.weights[r] * half_u * half_v;
          shape = mesh.shape_values(u, v);
          element += weight * (f.membrane_u * shape.d_u * shape.d_u.transpose() +
                               f.membrane_v * shape.d_v * shape.d_v.transpose() +
                               f.mass * shape.value * shape.value.transpose());
        }
      }
      // The active nodes of an interior point are the same everywhere in the cell.
      for (int a = 0; a < shape.active_count; ++a) {
        for (int b = 0; b < shape.active_count; ++b) {
          entries.emplace_back(shape.node[a], shape.node[b], element(a, b));
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(mesh.node_count(), mesh.node_count());
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

void check_points(int points_per_direction) {
  if (points_per_direction < 1 || points_per_direction > kMaxGaussPoints) {
    throw make_error("parametric FE mesh: quadrature points per direction is ",
                     points_per_direction, "; it must be in 1..", kMaxGaussPoints);
  }
}

}  // namespace

std::vector<ParameterQuadraturePoint> ParametricFeMesh::quadrature_points(
    int points_per_direction) const {
  check_points(points_per_direction);
  const GaussLegendreRule& rule = gauss_legendre_rule(points_per_direction);
  std::vector<ParameterQuadraturePoint> points;
  points.reserve(static_cast<size_t>(cells_u_) * cells_v_ * points_per_direction *
                 points_per_direction);
  for (int i = 0; i < cells_u_; ++i) {
    for (int j = 0; j < cells_v_; ++j) {
      const Eigen::Vector4d box = cell_bounds(i, j);
      const double half_u = 0.5 * (box[1] - box[0]);
      const double half_v = 0.5 * (box[3] - box[2]);
      for (int p = 0; p < points_per_direction; ++p) {
        for (int r = 0; r < points_per_direction; ++r) {
          points.push_back({box[0] + half_u * (rule.nodes[p] + 1.0),
                            box[2] + half_v * (rule.nodes[r] + 1.0),
                            rule.weights[p] * rule.weights[r] * half_u * half_v, i, j});
        }
      }
    }
  }
  return points;
}

Eigen::SparseMatrix<double> ParametricFeMesh::scalar_stiffness_matrix(
    const FeStiffnessCoefficients& coefficients, int points_per_direction) const {
  check_points(points_per_direction);
  const std::pair<const char*, double> checks[] = {{"membrane_u", coefficients.membrane_u},
                                                   {"membrane_v", coefficients.membrane_v},
                                                   {"spring", coefficients.spring}};
  for (const auto& [name, value] : checks) {
    if (!std::isfinite(value) || value < 0.0) {
      throw make_error("parametric FE mesh: stiffness coefficient ", name, " is ", value,
                       "; it must be finite and non-negative");
    }
  }
  return assemble_scalar(*this,
                         {coefficients.membrane_u, coefficients.membrane_v, coefficients.spring},
                         points_per_direction);
}

Eigen::SparseMatrix<double> ParametricFeMesh::stiffness_matrix(
    const FeStiffnessCoefficients& coefficients, int points_per_direction) const {
  return kronecker_identity(scalar_stiffness_matrix(coefficients, points_per_direction), 3);
}

Eigen::SparseMatrix<double> ParametricFeMesh::scalar_mass_matrix(int points_per_direction) const {
  check_points(points_per_direction);
  return assemble_scalar(*this, {0.0, 0.0, 1.0}, points_per_direction);
}

}  // namespace dnurbs
