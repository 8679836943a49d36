#include "dnurbs/dynamics/integrators/step_blocks.h"

#include <limits>
#include <optional>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"

namespace dnurbs {

namespace {

using RowMatrixX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using NodeMap = Eigen::Map<RowMatrixX3>;
using ConstNodeMap = Eigen::Map<const RowMatrixX3>;

// M + c_D D + c_K K (an empty D and zero coefficients are skipped, so that c_D = c_K = 0
// factors M with its own pattern).
SparseMatrix effective_matrix(const ModelMatrices& matrices, double damping_coefficient,
                              double stiffness_coefficient) {
  SparseMatrix result = matrices.mass;
  if (stiffness_coefficient != 0.0) {
    result += stiffness_coefficient * matrices.stiffness;
  }
  if (damping_coefficient != 0.0 && matrices.damping.nonZeros() > 0) {
    result += damping_coefficient * matrices.damping;
  }
  return result;
}

// The Error of a block whose step matrix could not be factored.
Error factorization_error(int model, Eigen::Index unknowns, const Error& error) {
  return make_error("the effective matrix A = M + c D + c' K of model ", model, " (", unknowns,
                    " free unknowns) could not be factored (", error.what(),
                    "): is some free coordinate without mass?");
}

LowRankSettings block_settings(LowRankSettings settings, bool constant) {
  if (constant) {
    // Factored once, solved every step: the solve-only crossover (core/sparse_cholesky.h)
    settings.cholesky.supernodal_threshold = settings.cholesky.constant_supernodal_threshold;
  } else {
    // Refactored at every iterate, and every term moves with L(q): folding would only refactor
    // once more.
    settings.max_woodbury_terms = std::numeric_limits<int>::max();
  }
  return settings;
}

}  // namespace

StepBlock::StepBlock(const System& system, int index, const LowRankSettings& settings)
    : model(index) {
  const Model& m = system.model(index);
  coordinate_offset = system.coordinate_offset(index);
  coordinate_count = m.coordinate_count();
  velocity_offset = system.velocity_offset(index);
  velocity_count = m.velocity_count();
  constant = m.matrices_are_constant() && m.constant_matrices() != nullptr;
  const std::vector<int>& fixed = m.fixed_coordinates();
  const std::optional<std::vector<int>> nodes = fixed_nodes(fixed, 3);
  kronecker = constant && m.kronecker_block_size() == 3 && m.scalar_matrices() != nullptr &&
              velocity_count % 3 == 0 && coordinate_count == velocity_count && nodes;
  free = kronecker ? FreeCoordinates(velocity_count / 3, *nodes)
                   : FreeCoordinates(velocity_count, fixed);
  if (kronecker) {
    const ModelMatrices& scalar = *m.scalar_matrices();
    residual =
        FreeRowProduct({&scalar.stiffness, &scalar.damping, &scalar.mass}, free.free_unknowns(), 3);
  }
  solver = LowRankUpdate(block_settings(settings, constant));
}

const ModelMatrices& StepBlock::full_matrices(const System& system) const {
  return constant ? *system.model(model).constant_matrices() : matrices;
}

BlockSprings::Layout StepBlock::spring_layout() const {
  return BlockSprings::Layout{model, coordinate_offset, kronecker, &free};
}

void StepBlock::factor(const System& system, double damping_coefficient,
                       double stiffness_coefficient, bool fold_springs) {
  const ModelMatrices& source =
      kronecker ? *system.model(model).scalar_matrices() : full_matrices(system);
  factored = false;
  lean_active = false;
  ++factorizations;
  if (free.free_count() > 0) {
    SparseMatrix reduced =
        free.reduce(effective_matrix(source, damping_coefficient, stiffness_coefficient));
    if (fold_springs) {
      springs.add_to_matrix(reduced);
    }
    try {
      solver.factorize(reduced);
    } catch (const Error& error) {
      throw factorization_error(model, reduced.rows(), error);
    }
  }
  position_coefficient = stiffness_coefficient;
  velocity_coefficient = damping_coefficient;
  factored = true;
}

bool StepBlock::factor_lean(double damping_coefficient, double stiffness_coefficient,
                            bool supernodal) {
  if (!lean.fits(matrices, supernodal) && !lean.analyze(matrices, free, supernodal)) {
    return false;
  }
  factored = false;
  lean_active = false;
  ++factorizations;
  try {
    lean.factorize(matrices, damping_coefficient, stiffness_coefficient);
  } catch (const Error& error) {
    throw factorization_error(model, free.free_count(), error);
  }
  position_coefficient = stiffness_coefficient;
  velocity_coefficient = damping_coefficient;
  factored = true;
  lean_active = true;
  return true;
}

void StepBlock::solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  const auto free_count = static_cast<Eigen::Index>(free.free_count());
  if (free_count == 0) {
    return;
  }
  if (lean_active) {
    lean.solve(r.data() + velocity_offset, x.data() + velocity_offset);
    return;
  }
  if (kronecker) {
    const ConstNodeMap R(r.data() + velocity_offset, velocity_count / 3, 3);
    NodeMap X(x.data() + velocity_offset, velocity_count / 3, 3);
    rhs_free.resize(free_count, 3);
    for (Eigen::Index i = 0; i < free_count; ++i) {
      rhs_free.row(i) = R.row(free.free_unknown(static_cast<int>(i)));
    }
    solver.solve_in_place(rhs_free);
    for (Eigen::Index i = 0; i < free_count; ++i) {
      X.row(free.free_unknown(static_cast<int>(i))) = rhs_free.row(i);
    }
  } else {
    rhs_free.resize(free_count, 1);
    for (Eigen::Index i = 0; i < free_count; ++i) {
      rhs_free(i, 0) = r[velocity_offset + free.free_unknown(static_cast<int>(i))];
    }
    solver.solve_in_place(rhs_free);
    for (Eigen::Index i = 0; i < free_count; ++i) {
      x[velocity_offset + free.free_unknown(static_cast<int>(i))] = rhs_free(i, 0);
    }
  }
}

void StepBlocks::layout(const System& system, const LowRankSettings& settings) {
  if (laid_out && revision == system.revision() && velocity_count == system.velocity_count() &&
      static_cast<int>(blocks.size()) == system.model_count()) {
    return;
  }
  blocks.clear();
  for (int i = 0; i < system.model_count(); ++i) {
    blocks.push_back(std::make_unique<StepBlock>(system, i, settings));
  }
  laid_out = true;
  revision = system.revision();
  velocity_count = system.velocity_count();
}

void StepBlocks::solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  x.setZero(r.size());
  for (const auto& block : blocks) {
    block->solve(r, x);
  }
}

}  // namespace dnurbs
