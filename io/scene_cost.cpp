#include "dnurbs/io/scene_cost.h"

#include <algorithm>
#include <optional>
#include <vector>

#include <Eigen/SparseCholesky>

#include "dnurbs/core/fixed_coordinates.h"
#include "dnurbs/core/kronecker.h"

namespace dnurbs {

namespace {

// Sizes of a symmetric pattern and of its LDL^T factor, and the work of one factorization.
struct FactorSize {
  long long matrix_non_zeros = 0;
  long long factor_non_zeros = 0;   // -1 if the pattern could not be factored
  double factorization_work = 0.0;  // sum over columns of (entries of L in the column)^2
};

FactorSize factor_size(const SparseMatrix& matrix) {
  // Values that make the pattern positive definite: the factor's pattern is what counts
  SparseMatrix a = matrix;
  Eigen::VectorXd row_count = Eigen::VectorXd::Zero(a.rows());
  for (int k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      it.valueRef() = it.row() == it.col() ? 0.0 : -1.0;
      row_count(it.row()) += 1.0;
    }
  }
  SparseMatrix diagonal(a.rows(), a.cols());
  diagonal.setIdentity();
  for (int i = 0; i < a.rows(); ++i) {
    diagonal.coeffRef(i, i) = row_count(i) + 1.0;
  }
  a += diagonal;
  FactorSize size;
  size.matrix_non_zeros = matrix.nonZeros();
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);  // AMD ordering, as the integrators use
  if (ldlt.info() != Eigen::Success) {
    size.factor_non_zeros = -1;
    return size;
  }
  const auto& factor = ldlt.matrixL().nestedExpression();
  size.factor_non_zeros = factor.nonZeros();
  for (int k = 0; k < factor.outerSize(); ++k) {
    const double column =
        static_cast<double>(factor.outerIndexPtr()[k + 1] - factor.outerIndexPtr()[k]);
    size.factorization_work += column * column;
  }
  return size;
}

}  // namespace

// Sizes and the work of one solve of a model at its initial state, fixed coordinates eliminated
SceneModelCost model_cost(const Model& model) {
  SceneModelCost c;
  c.coordinates = model.coordinate_count();
  c.velocities = model.velocity_count();
  std::vector<int> fixed = model.fixed_coordinates();
  std::sort(fixed.begin(), fixed.end());
  c.fixed = static_cast<int>(fixed.size());
  c.constant_matrices = model.matrices_are_constant();
  c.kronecker_block = model.kronecker_block_size();
  ModelMatrices matrices;
  const std::optional<std::vector<int>> nodes =
      c.kronecker_block > 0 ? fixed_nodes(fixed, c.kronecker_block) : std::nullopt;
  int unknowns = model.velocity_count();
  if (nodes && model.scalar_matrices() != nullptr) {
    // The scalar matrix, a node eliminated when all of its x, y, z are fixed
    matrices = *model.scalar_matrices();
    fixed = *nodes;
    unknowns /= c.kronecker_block;
  } else {
    model.assemble_matrices(model.initial_coordinates(), matrices);
  }
  SparseMatrix sum = matrices.mass;
  if (matrices.damping.nonZeros() > 0) {
    sum += matrices.damping;
  }
  if (matrices.stiffness.nonZeros() > 0) {
    sum += matrices.stiffness;
  }
  // The christoffel Terzopoulos stiffness is not symmetric: factor its symmetric pattern
  const SparseMatrix transposed = sum.transpose();
  sum += transposed;
  const FactorSize size = factor_size(FreeCoordinates(unknowns, fixed).reduce(sum));
  c.matrix_non_zeros = size.matrix_non_zeros;
  c.factor_non_zeros = size.factor_non_zeros;
  // One solve: a forward and a backward substitution per right-hand side with a constant
  // factor; a factorization first when the matrices change with the state
  const int right_hand_sides = c.kronecker_block > 0 ? c.kronecker_block : 1;
  c.solve_work = 2.0 * static_cast<double>(size.factor_non_zeros) * right_hand_sides +
                 (c.constant_matrices ? 0.0 : size.factorization_work);
  return c;
}

}  // namespace dnurbs
