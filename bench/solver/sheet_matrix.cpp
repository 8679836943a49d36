#include "bench/solver/sheet_matrix.h"

#include <Eigen/Dense>

#include "dnurbs/nurbs/basis_functions.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs::bench {

namespace {

// One-dimensional Gram matrices of the clamped cubic basis: row d of `gram` holds
// integral N^(d) N^(d)^T for d = 0, 1, 2 (dense side by side; the band is 7 wide).
std::array<Eigen::MatrixXd, 3> gram_matrices(const KnotVector& knots) {
  const int count = knots.basis_count();
  std::array<Eigen::MatrixXd, 3> gram;
  for (Eigen::MatrixXd& g : gram) {
    g = Eigen::MatrixXd::Zero(count, count);
  }
  BasisDerivatives derivatives;
  for (const int span : knots.non_empty_spans()) {
    const GaussLegendreRule rule = gauss_legendre_rule_on(4, knots[span], knots[span + 1]);
    for (Eigen::Index q = 0; q < rule.nodes.size(); ++q) {
      basis_functions_with_derivatives(knots, span, rule.nodes[q], 2, derivatives);
      for (int d = 0; d < 3; ++d) {
        for (int a = 0; a <= 3; ++a) {
          for (int b = 0; b <= 3; ++b) {
            gram[static_cast<size_t>(d)](span - 3 + a, span - 3 + b) +=
                rule.weights[q] * derivatives(d, a) * derivatives(d, b);
          }
        }
      }
    }
  }
  return gram;
}

}  // namespace

SheetMatrix make_sheet_matrix(int side) {
  constexpr double kMassDensity = 1.0, kDamping = 1.0, kTension = 1.0, kRigidity = 1e-3;
  constexpr double kTimeStep = 1.0 / 60.0;
  SheetMatrix sheet;
  sheet.side = side;
  sheet.knots = KnotVector::clamped_uniform(3, side);
  const auto [m, k1, k2] = gram_matrices(sheet.knots);
  const double mass_coefficient =
      kMassDensity / (kTimeStep * kTimeStep) + kDamping / (2.0 * kTimeStep);
  const int n = side * side;
  Eigen::SparseMatrix<double>& a = sheet.step_matrix;
  a.resize(n, n);
  a.reserve(Eigen::VectorXi::Constant(n, 49));
  for (int i2 = 0; i2 < side; ++i2) {
    for (int j2 = 0; j2 < side; ++j2) {
      const int column = i2 * side + j2;
      for (int i1 = std::max(0, i2 - 3); i1 <= std::min(side - 1, i2 + 3); ++i1) {
        for (int j1 = std::max(0, j2 - 3); j1 <= std::min(side - 1, j2 + 3); ++j1) {
          // Tensor-product integrals: the (u, v) integrand factors into two 1D Gram entries.
          const double mm = m(i1, i2) * m(j1, j2);
          const double value =
              mass_coefficient * mm + kTension * (k1(i1, i2) * m(j1, j2) + m(i1, i2) * k1(j1, j2)) +
              kRigidity *
                  (k2(i1, i2) * m(j1, j2) + 2.0 * k1(i1, i2) * k1(j1, j2) + m(i1, i2) * k2(j1, j2));
          a.insert(i1 * side + j1, column) = value;
        }
      }
    }
  }
  a.makeCompressed();
  return sheet;
}

SpringBasis spring_basis(const SheetMatrix& sheet, double u, double v) {
  SpringBasis basis;
  BasisValues nu, nv;
  const int span_u = sheet.knots.find_span(u);
  const int span_v = sheet.knots.find_span(v);
  basis_functions(sheet.knots, span_u, u, nu);
  basis_functions(sheet.knots, span_v, v, nv);
  for (int a = 0; a <= 3; ++a) {
    for (int b = 0; b <= 3; ++b) {
      const size_t p = 4 * static_cast<size_t>(a) + static_cast<size_t>(b);
      basis.rows[p] = (span_u - 3 + a) * sheet.side + (span_v - 3 + b);
      basis.values[p] = nu[a] * nv[b];
    }
  }
  return basis;
}

}  // namespace dnurbs::bench
