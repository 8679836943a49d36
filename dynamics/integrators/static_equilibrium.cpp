#include "dnurbs/dynamics/integrators/static_equilibrium.h"

#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// Sum over the springs at the system's time of k L^T L (velocity space, stacked), with k L^T
// target added to `rhs`.
SparseMatrix spring_stiffness(const System& system, Eigen::VectorXd& rhs) {
  const int n = system.velocity_count();
  SparseMatrix result(n, n);
  for (int id = 0; id < system.spring_id_count(); ++id) {
    if (!system.has_spring(id)) {
      continue;
    }
    const SpringState state = system.spring_state(id, system.time());
    const int i = system.spring_model(id);
    const SparseMatrix local =
        system.model(i).position_jacobian(system.coordinates(i), state.parameter);
    SparseMatrix jacobian(3, n);  // L in the stacked velocity space
    std::vector<Eigen::Triplet<double>> triplets;
    for (Eigen::Index j = 0; j < local.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(local, j); it; ++it) {
        triplets.emplace_back(static_cast<int>(it.row()),
                              system.velocity_offset(i) + static_cast<int>(j), it.value());
      }
    }
    jacobian.setFromTriplets(triplets.begin(), triplets.end());
    result += state.stiffness * SparseMatrix(jacobian.transpose() * jacobian);
    rhs += state.stiffness * (jacobian.transpose() * state.target);
  }
  return result;
}

}  // namespace

void solve_static_equilibrium(System& system) {
  if (!system.matrices_are_constant()) {
    throw make_error("static equilibrium K q = f needs constant matrices (a system with ",
                     system.model_count(), " models has state-dependent ones)");
  }
  const int n = system.velocity_count();
  if (n != system.coordinate_count()) {
    throw make_error("static equilibrium needs coordinates and velocities of the same size (",
                     system.coordinate_count(), " and ", n, ")");
  }
  const Eigen::VectorXd& q = system.coordinates();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  // K plus the springs' k L^T L, f plus their k L^T target: a spring's force k L^T (target - L q)
  // is linear in q (L constant for constant-matrix models). The internal force of a
  // constant-matrix model is affine, f_int(q) = f_int(0) - K q (f_int(0) = K q_r with a rest
  // shape q_r, dnurbs_model.h), so f_int(0) joins the right-hand side.
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  system.add_internal_forces(zero, rhs);
  system.add_applied_forces(system.time(), q, zero, rhs, /*include_springs=*/false);
  const SparseMatrix K = spring_stiffness(system, rhs) + system.constant_matrices()->stiffness;

  // Right-hand side f - K q_c: the fixed coordinates at their values, the free ones at zero.
  std::vector<int> free_index(static_cast<size_t>(n), 0);
  for (const int index : system.fixed_coordinates()) {
    free_index[static_cast<size_t>(index)] = -1;
  }
  Eigen::VectorXd held = Eigen::VectorXd::Zero(n);
  std::vector<int> free_list;
  for (int i = 0; i < n; ++i) {
    if (free_index[static_cast<size_t>(i)] >= 0) {
      free_index[static_cast<size_t>(i)] = static_cast<int>(free_list.size());
      free_list.push_back(i);
    } else {
      held[i] = q[i];
    }
  }
  rhs.noalias() -= K * held;

  // K_ff by selection of the free rows and columns.
  const auto free_count = static_cast<int>(free_list.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(K.nonZeros()));
  for (Eigen::Index j = 0; j < K.outerSize(); ++j) {
    const int fj = free_index[static_cast<size_t>(j)];
    if (fj < 0) {
      continue;
    }
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
      const int fi = free_index[static_cast<size_t>(it.row())];
      if (fi >= 0) {
        triplets.emplace_back(fi, fj, it.value());
      }
    }
  }
  SparseMatrix reduced(free_count, free_count);
  reduced.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd rhs_free(free_count);
  for (int i = 0; i < free_count; ++i) {
    rhs_free[i] = rhs[free_list[static_cast<size_t>(i)]];
  }
  Eigen::SimplicialLDLT<SparseMatrix> solver(reduced);
  if (solver.info() != Eigen::Success) {
    throw make_error("the free stiffness matrix (", free_count,
                     " coordinates) is singular: fix enough coordinates");
  }
  const Eigen::VectorXd solution = solver.solve(rhs_free);
  // LDLT of a singular PSD matrix may "succeed" with a zero pivot: check the residual.
  const double residual = (reduced * solution - rhs_free).norm();
  if (!solution.allFinite() || residual > 1e-8 * std::max(1.0, rhs_free.norm())) {
    throw make_error("the free stiffness matrix (", free_count,
                     " coordinates) is singular (residual ", residual, "): fix enough coordinates");
  }
  Eigen::VectorXd q_new = q;
  for (int i = 0; i < free_count; ++i) {
    q_new[free_list[static_cast<size_t>(i)]] = solution[i];
  }
  system.set_state(q_new, zero, system.time());
}

}  // namespace dnurbs
