#include "dynamics/integrators/static_equilibrium.h"

#include <cmath>

#include <Eigen/SparseCholesky>

#include "core/error.h"

namespace dnurbs {

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
  const SparseMatrix& K = system.constant_matrices()->stiffness;
  const Eigen::VectorXd& q = system.coordinates();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);

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
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  system.add_applied_forces(system.time(), q, zero, rhs);
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
