#include "dnurbs/dynamics/triangular/triangular_free_weight_terms.h"

#include <algorithm>

namespace dnurbs {

void add_transposed_jacobian_times(const TriangularBasisValues& basis,
                                   const TriangularRationalJacobian& jacobian, int alpha,
                                   bool free_weights, const Eigen::Vector3d& f, VectorRef force) {
  const int stride = free_weights ? 4 : 3;
  for (int a = 0; a < basis.count; ++a) {
    const int offset = basis.function[static_cast<size_t>(a)] * stride;
    force.segment<3>(offset) += jacobian.rational(alpha, a) * f;
    if (free_weights) {
      force[offset + 3] += jacobian.weight_column[static_cast<size_t>(alpha)].col(a).dot(f);
    }
  }
}

void add_free_weight_terms(const TriangularRationalJacobian& jacobian,
                           const std::array<double, 6>& coefficient, int count,
                           const std::vector<int>& local, int local_count,
                           std::vector<double>& block) {
  const int size = 4 * local_count;
  for (int alpha = 0; alpha < 6; ++alpha) {
    const double c = coefficient[static_cast<size_t>(alpha)];
    if (c == 0.0) {
      continue;
    }
    const auto& columns = jacobian.weight_column[static_cast<size_t>(alpha)];
    for (int i = 0; i < count; ++i) {
      const double ri = jacobian.rational(alpha, i);
      const int first_row = 4 * local[static_cast<size_t>(i)] * size;
      double* row = block.data() + first_row;
      for (int j = 0; j < count; ++j) {
        const double rj = jacobian.rational(alpha, j);
        const int column = 4 * local[static_cast<size_t>(j)];
        const double s = c * (ri * rj);
        for (int r = 0; r < 3; ++r) {
          row[r * size + column + r] += s;
          row[r * size + column + 3] += c * (ri * columns(r, j));
          row[3 * size + column + r] += c * (columns(r, i) * rj);
        }
        row[3 * size + column + 3] += c * columns.col(i).dot(columns.col(j));
      }
    }
  }
}

void scatter_free_weight_block(const AssemblyPattern& pattern, const SparseMatrix& block_pattern,
                               int element, int element_local, const std::vector<double>& block,
                               SparseMatrix& matrix) {
  const int local = pattern.local_count;
  const int size = 4 * local;
  const int* to_value =
      &pattern.local_to_value[static_cast<size_t>(element) * static_cast<size_t>(local * local)];
  const int* nodes =
      &pattern.element_nodes[static_cast<size_t>(element) * static_cast<size_t>(local)];
  for (int a = 0; a < element_local; ++a) {
    for (int b = 0; b < element_local; ++b) {
      const int s = to_value[a * local + b];
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
          const int index =
              dense_block_value_index(block_pattern, pattern.scalar, s, nodes[b], r, c, 4);
          const int entry = (4 * a + r) * size + 4 * b + c;
          matrix.valuePtr()[index] += block[static_cast<size_t>(entry)];
        }
      }
    }
  }
}

void reset_to_pattern(const SparseMatrix& pattern, bool used, SparseMatrix& matrix) {
  const bool same_structure = matrix.isCompressed() && matrix.rows() == pattern.rows() &&
                              matrix.cols() == pattern.cols() &&
                              matrix.nonZeros() == pattern.nonZeros();
  if (!used) {
    matrix = SparseMatrix(pattern.rows(), pattern.cols());
  } else if (same_structure) {
    Eigen::Map<Eigen::VectorXd>(matrix.valuePtr(), matrix.nonZeros()).setZero();
  } else {
    matrix = pattern;
  }
}

}  // namespace dnurbs
