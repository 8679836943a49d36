#pragma once
// The cost report of a scene's models (SceneSimulation::cost, `dnurbs info`): the size of each
// model's step matrix and of its LDL^T factor, and the work of one solve.

#include <string>

#include "dnurbs/dynamics/core/model.h"

namespace dnurbs {

/// Size and cost of one model (at its initial state, fixed coordinates eliminated), and what
/// the library's automatic choice for it saves against the naive path.
struct SceneModelCost {
  std::string name;
  std::string type;
  int coordinates = 0;
  int velocities = 0;
  int fixed = 0;                   ///< fixed velocity coordinates
  bool constant_matrices = false;  ///< M, D, K assembled and factored once
  int kronecker_block = 0;         ///< 3 when x, y, z share one scalar matrix
  /// Non-zeros of M + D + K over the free coordinates (of the scalar matrix when
  /// kronecker_block), and of L of its LDL^T factor (AMD ordering, as the integrators use)
  long long matrix_non_zeros = 0;
  long long factor_non_zeros = 0;
  /// Work of one solve in factor entries touched: 2 nnz(L) per right-hand side, plus the
  /// factorization (sum of squared column counts of L) when the matrices change with the state
  double solve_work = 0.0;
  /// The automatic choice (fixed weights, rigid or global superquadric parts, deformation
  /// regions; empty when the model takes the naive path) and the naive path's active
  /// coordinates, matrix kind and solve work
  std::string automatic_choice;
  int naive_active = 0;
  bool naive_constant_matrices = false;
  double naive_solve_work = 0.0;
};

/// The sizes and solve work of `model` at its initial state (name, type and the naive path are
/// the caller's): the scalar matrix when the model has the S (x) I_b layout and its fixed
/// coordinates come in whole nodes, else M + D + K, fixed coordinates eliminated.
SceneModelCost model_cost(const Model& model);

}  // namespace dnurbs
