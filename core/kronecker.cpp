#include "dnurbs/core/kronecker.h"

#include "dnurbs/core/error.h"

namespace dnurbs {

SparseMatrix kronecker_identity(const SparseMatrix& scalar, int block_size) {
  if (block_size < 1) {
    throw make_error("Kronecker block size ", block_size, " must be at least 1");
  }
  const auto n = scalar.rows();
  SparseMatrix result(n * block_size, scalar.cols() * block_size);
  Eigen::VectorXi sizes(scalar.cols() * block_size);
  for (Eigen::Index j = 0; j < scalar.cols(); ++j) {
    for (int c = 0; c < block_size; ++c) {
      sizes[j * block_size + c] = static_cast<int>(scalar.col(j).nonZeros());
    }
  }
  result.reserve(sizes);
  for (Eigen::Index j = 0; j < scalar.outerSize(); ++j) {
    for (int c = 0; c < block_size; ++c) {
      for (SparseMatrix::InnerIterator it(scalar, j); it; ++it) {
        result.insert(it.row() * block_size + c, j * block_size + c) = it.value();
      }
    }
  }
  result.makeCompressed();
  return result;
}

std::optional<std::vector<int>> fixed_nodes(const std::vector<int>& fixed, int block_size) {
  if (block_size < 1) {
    throw make_error("Kronecker block size ", block_size, " must be at least 1");
  }
  const auto block = static_cast<size_t>(block_size);
  if (fixed.size() % block != 0) {
    return std::nullopt;
  }
  std::vector<int> nodes;
  nodes.reserve(fixed.size() / block);
  for (size_t i = 0; i < fixed.size(); i += block) {
    if (fixed[i] % block_size != 0) {
      return std::nullopt;
    }
    for (size_t c = 1; c < block; ++c) {
      if (fixed[i + c] != fixed[i] + static_cast<int>(c)) {
        return std::nullopt;
      }
    }
    nodes.push_back(fixed[i] / block_size);
  }
  return nodes;
}

namespace {

void check_quadratic_form(const SparseMatrix& scalar, Eigen::Index size, int block_size) {
  if (block_size < 1) {
    throw make_error("Kronecker block size ", block_size, " must be at least 1");
  }
  if (scalar.rows() != scalar.cols() || size != scalar.rows() * block_size) {
    throw make_error("Kronecker quadratic form: the scalar matrix is ", scalar.rows(), " by ",
                     scalar.cols(), ", the vector has ", size, " entries (block size ", block_size,
                     ")");
  }
}

// sum_ij S_ij <z_i, z_j> over the stored entries of S, with component c of z_i = node(i, c).
template <typename NodeValue>
double quadratic_form_over_pattern(const SparseMatrix& scalar, int block_size,
                                   const NodeValue& node) {
  double sum = 0.0;
  for (Eigen::Index j = 0; j < scalar.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(scalar, j); it; ++it) {
      double dot = 0.0;
      for (int c = 0; c < block_size; ++c) {
        dot += node(it.row(), c) * node(j, c);
      }
      sum += it.value() * dot;
    }
  }
  return sum;
}

}  // namespace

double kronecker_quadratic_form(const SparseMatrix& scalar,
                                const Eigen::Ref<const Eigen::VectorXd>& x, int block_size) {
  check_quadratic_form(scalar, x.size(), block_size);
  const double* data = x.data();
  return quadratic_form_over_pattern(
      scalar, block_size, [&](Eigen::Index i, int c) { return data[i * block_size + c]; });
}

double kronecker_quadratic_form_of_difference(const SparseMatrix& scalar,
                                              const Eigen::Ref<const Eigen::VectorXd>& x,
                                              const Eigen::Ref<const Eigen::VectorXd>& y,
                                              int block_size) {
  check_quadratic_form(scalar, x.size(), block_size);
  if (y.size() != x.size()) {
    throw make_error("Kronecker quadratic form of a difference: the vectors have ", x.size(),
                     " and ", y.size(), " entries");
  }
  const double* xs = x.data();
  const double* ys = y.data();
  return quadratic_form_over_pattern(scalar, block_size, [&](Eigen::Index i, int c) {
    const Eigen::Index k = i * block_size + c;
    return xs[k] - ys[k];
  });
}

}  // namespace dnurbs
