#include "dnurbs/dynamics/core/quadrature_assembly.h"

#include <algorithm>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {

DirectionQuadrature direction_quadrature(const KnotVector& knots, int points_per_span) {
  const GaussLegendreRule& rule = gauss_legendre_rule(points_per_span);
  DirectionQuadrature table;
  table.degree = knots.degree();
  table.points_per_span = points_per_span;
  const std::vector<int> spans = knots.non_empty_spans();
  table.span_count = static_cast<int>(spans.size());
  const int p = table.degree;
  const auto point_total = static_cast<size_t>(table.span_count * points_per_span);
  table.control_point.resize(spans.size() * static_cast<size_t>(p + 1));
  table.parameter.resize(point_total);
  table.weight.resize(point_total);
  table.basis.resize(point_total * 3 * static_cast<size_t>(p + 1));
  table.span_start.resize(spans.size());
  table.span_end.resize(spans.size());
  BasisDerivatives derivatives;
  for (int s = 0; s < table.span_count; ++s) {
    const int k = spans[static_cast<size_t>(s)];
    const double a = knots[k];
    const double b = knots[k + 1];
    table.span_start[static_cast<size_t>(s)] = a;
    table.span_end[static_cast<size_t>(s)] = b;
    for (int j = 0; j <= p; ++j) {
      table.control_point[static_cast<size_t>(s * (p + 1) + j)] = knots.control_point_index(k, j);
    }
    for (int g = 0; g < points_per_span; ++g) {
      const int i = s * points_per_span + g;
      const double u = a + 0.5 * (b - a) * (rule.nodes[g] + 1.0);
      table.parameter[static_cast<size_t>(i)] = u;
      table.weight[static_cast<size_t>(i)] = 0.5 * (b - a) * rule.weights[g];
      basis_functions_with_derivatives(knots, k, u, 2, derivatives);
      for (int d = 0; d < 3; ++d) {
        for (int j = 0; j <= p; ++j) {
          table.basis[static_cast<size_t>((i * 3 + d) * (p + 1) + j)] = derivatives(d, j);
        }
      }
    }
  }
  return table;
}

DirectionQuadrature trivial_direction_quadrature() {
  DirectionQuadrature table;
  table.control_point = {0};
  table.parameter = {0.0};
  table.weight = {1.0};
  table.basis = {1.0, 0.0, 0.0};
  table.span_start = {0.0};
  table.span_end = {1.0};
  return table;
}

void direction_basis(const KnotVector& knots, double u, DirectionBasis& basis) {
  const double x = knots.to_domain(u);
  const int k = knots.find_span(x);
  BasisDerivatives derivatives;
  basis_functions_with_derivatives(knots, k, x, 2, derivatives);
  basis.degree = knots.degree();
  for (int j = 0; j <= basis.degree; ++j) {
    basis.control_point[static_cast<size_t>(j)] = knots.control_point_index(k, j);
    for (int d = 0; d < 3; ++d) {
      basis.value(d, j) = derivatives(d, j);
    }
  }
}

void trivial_direction_basis(DirectionBasis& basis) {
  basis.degree = 0;
  basis.control_point[0] = 0;
  basis.value.col(0) << 1.0, 0.0, 0.0;
}

void direction_basis(const DirectionQuadrature& table, int span, int point, DirectionBasis& basis) {
  const int p = table.degree;
  basis.degree = p;
  const int i = span * table.points_per_span + point;
  for (int j = 0; j <= p; ++j) {
    basis.control_point[static_cast<size_t>(j)] =
        table.control_point[static_cast<size_t>(span * (p + 1) + j)];
    for (int d = 0; d < 3; ++d) {
      basis.value(d, j) = table.basis[static_cast<size_t>((i * 3 + d) * (p + 1) + j)];
    }
  }
}

void tensor_product_basis(const DirectionBasis& basis_u, const DirectionBasis& basis_v, int count_v,
                          PointBasis& basis) {
  const int nu = basis_u.degree + 1;
  const int nv = basis_v.degree + 1;
  basis.active_count = nu * nv;
  basis.value.resize(kQuantityCount, basis.active_count);
  for (int a = 0; a < nu; ++a) {
    for (int b = 0; b < nv; ++b) {
      const int local = a * nv + b;
      basis.node[static_cast<size_t>(local)] =
          basis_u.control_point[static_cast<size_t>(a)] * count_v +
          basis_v.control_point[static_cast<size_t>(b)];
      for (int alpha = 0; alpha < kQuantityCount; ++alpha) {
        basis.value(alpha, local) = basis_u.value(kQuantityOrderU[static_cast<size_t>(alpha)], a) *
                                    basis_v.value(kQuantityOrderV[static_cast<size_t>(alpha)], b);
      }
    }
  }
}

void rational_jacobian(const PointBasis& basis, int order, const ControlNet& net,
                       bool with_weight_columns, RationalJacobian& jacobian) {
  const int n = basis.active_count;
  const int quantities = quantity_count(order);
  jacobian.order = order;
  jacobian.rational.resize(kQuantityCount, n);
  jacobian.phi.resize(kQuantityCount, n);

  // Weight function W^alpha = sum_a w_a N_a^alpha.
  std::array<double, kQuantityCount> weight_sum{};
  for (int a = 0; a < n; ++a) {
    const double w = net.weights[basis.node[static_cast<size_t>(a)] * net.weight_stride];
    for (int alpha = 0; alpha < quantities; ++alpha) {
      weight_sum[static_cast<size_t>(alpha)] += w * basis.value(alpha, a);
    }
  }
  const double W = weight_sum[0];
  jacobian.weight_sum = W;
  const double inverse_W = 1.0 / W;

  // phi_a = N_a / W by the quotient rule: W phi^alpha = N^alpha - sum_{beta != 0} c W^beta
  // phi^rest.
  for (int alpha = 0; alpha < quantities; ++alpha) {
    const auto first = static_cast<size_t>(kLeibnizFirst[static_cast<size_t>(alpha)]);
    const auto last = static_cast<size_t>(kLeibnizFirst[static_cast<size_t>(alpha) + 1]);
    for (int a = 0; a < n; ++a) {
      double value = basis.value(alpha, a);
      for (size_t t = first + 1; t < last; ++t) {  // the terms with beta != 0
        const LeibnizTerm& term = kLeibnizTerms[t];
        value -= term.coefficient * weight_sum[static_cast<size_t>(term.beta)] *
                 jacobian.phi(term.rest, a);
      }
      jacobian.phi(alpha, a) = value * inverse_W;
    }
  }

  // R_a^alpha = w_a phi_a^alpha and x^alpha = sum_a R_a^alpha P_a (x is homogeneous of degree 0
  // in the weights, so x^alpha = J^alpha q exactly).
  for (int alpha = 0; alpha < quantities; ++alpha) {
    jacobian.point[static_cast<size_t>(alpha)].setZero();
  }
  for (int a = 0; a < n; ++a) {
    const int node = basis.node[static_cast<size_t>(a)];
    const double w = net.weights[node * net.weight_stride];
    const Eigen::Map<const Eigen::Vector3d> position(net.positions + node * net.position_stride);
    for (int alpha = 0; alpha < quantities; ++alpha) {
      const double r = w * jacobian.phi(alpha, a);
      jacobian.rational(alpha, a) = r;
      jacobian.point[static_cast<size_t>(alpha)] += r * position;
    }
  }
  if (!with_weight_columns) {
    return;
  }

  // E_a^alpha = D^alpha [phi_a (P_a - x)] = phi_a^alpha P_a - sum_{beta <= alpha} c phi^beta
  // x^rest.
  for (int alpha = 0; alpha < quantities; ++alpha) {
    auto& column = jacobian.weight_column[static_cast<size_t>(alpha)];
    column.resize(3, n);
    const auto first = static_cast<size_t>(kLeibnizFirst[static_cast<size_t>(alpha)]);
    const auto last = static_cast<size_t>(kLeibnizFirst[static_cast<size_t>(alpha) + 1]);
    for (int a = 0; a < n; ++a) {
      const int node = basis.node[static_cast<size_t>(a)];
      const Eigen::Map<const Eigen::Vector3d> position(net.positions + node * net.position_stride);
      Eigen::Vector3d value = jacobian.phi(alpha, a) * position -
                              jacobian.phi(0, a) * jacobian.point[static_cast<size_t>(alpha)];
      for (size_t t = first + 1; t < last; ++t) {  // the terms with beta != 0
        const LeibnizTerm& term = kLeibnizTerms[t];
        value -= term.coefficient * jacobian.phi(term.beta, a) *
                 jacobian.point[static_cast<size_t>(term.rest)];
      }
      column.col(a) = value;
    }
  }
}

AssemblyPattern make_assembly_pattern(int node_count, int local_count,
                                      const std::vector<int>& element_nodes) {
  AssemblyPattern pattern;
  pattern.node_count = node_count;
  pattern.local_count = local_count;
  pattern.element_nodes = element_nodes;
  const size_t element_count = element_nodes.size() / static_cast<size_t>(local_count);
  const auto local = static_cast<size_t>(local_count);

  // Pattern from the element couplings (triplets reserved once).
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(element_count * local * local);
  for (size_t e = 0; e < element_count; ++e) {
    for (size_t a = 0; a < local; ++a) {
      for (size_t b = 0; b < local; ++b) {
        triplets.emplace_back(element_nodes[e * local + a], element_nodes[e * local + b], 0.0);
      }
    }
  }
  pattern.scalar.resize(node_count, node_count);
  pattern.scalar.setFromTriplets(triplets.begin(), triplets.end());
  pattern.scalar.makeCompressed();

  // Index of every local pair in the value array (binary search in its column, once).
  pattern.local_to_value.resize(element_count * local * local);
  const auto* outer = pattern.scalar.outerIndexPtr();
  const auto* inner = pattern.scalar.innerIndexPtr();
  for (size_t e = 0; e < element_count; ++e) {
    for (size_t a = 0; a < local; ++a) {
      for (size_t b = 0; b < local; ++b) {
        const int row = element_nodes[e * local + a];
        const int column = element_nodes[e * local + b];
        const auto* found = std::lower_bound(inner + outer[column], inner + outer[column + 1], row);
        pattern.local_to_value[(e * local + a) * local + b] = static_cast<int>(found - inner);
      }
    }
  }
  return pattern;
}

SparseMatrix dense_block_pattern(const SparseMatrix& scalar, int block_size) {
  const auto n = scalar.rows();
  SparseMatrix result(n * block_size, n * block_size);
  Eigen::VectorXi sizes(n * block_size);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (int c = 0; c < block_size; ++c) {
      sizes[j * block_size + c] = static_cast<int>(scalar.col(j).nonZeros()) * block_size;
    }
  }
  result.reserve(sizes);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (int c = 0; c < block_size; ++c) {
      for (SparseMatrix::InnerIterator it(scalar, j); it; ++it) {
        for (int r = 0; r < block_size; ++r) {
          result.insert(it.row() * block_size + r, j * block_size + c) = 0.0;
        }
      }
    }
  }
  result.makeCompressed();
  return result;
}

}  // namespace dnurbs
