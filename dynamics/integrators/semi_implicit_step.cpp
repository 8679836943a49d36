#include "dnurbs/dynamics/integrators/semi_implicit_step.h"

#include <cmath>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"

namespace dnurbs {

namespace {

void append(const SparseMatrix& a, int offset, double scale,
            std::vector<Eigen::Triplet<double>>& out) {
  for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      out.emplace_back(offset + static_cast<int>(it.row()), offset + static_cast<int>(it.col()),
                       scale * it.value());
    }
  }
}

}  // namespace

void SemiImplicitStepper::step(System& system, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw make_error("time step dt = ", dt, " must be positive and finite");
  }
  const int n = system.velocity_count();
  if (system.coordinate_count() != n) {
    throw make_error(
        "the semi-implicit step needs models whose velocities are the time "
        "derivatives of their coordinates (",
        system.coordinate_count(), " coordinates, ", n, " velocities)");
  }
  const Eigen::VectorXd& q = system.coordinates();
  Eigen::VectorXd v = system.velocities();
  const std::vector<int>& fixed = system.fixed_coordinates();
  for (const int index : fixed) {
    v[index] = 0.0;
  }
  const double t = system.time();

  // Eq 1.13 for the increment Delta = q_{t+dt} - q_t (round-off then does not accumulate in a
  // state at rest): A Delta = f + g + f_int(q_t) + (M/dt - D/2) v_t, with v_t = (q_t - q_{t-dt})/dt
  // and f_int(q_t) = -K(q_t) q_t (+ an affine model's constant force).
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  system.add_applied_forces(t, q, v, rhs);
  system.add_inertial_forces(q, v, rhs);
  system.add_internal_forces(q, rhs);

  // Node layout (every model S (x) I_3 with whole nodes fixed): one scalar matrix, x, y and z
  // as three right-hand sides; otherwise one matrix over every coordinate.
  bool nodal = n % 3 == 0 && fixed_nodes(fixed, 3).has_value();
  for (int m = 0; m < system.model_count() && nodal; ++m) {
    nodal = system.velocity_offset(m) % 3 == 0 && system.model(m).semi_implicit_block_size() == 3;
  }
  const int block = nodal ? 3 : 1;
  const int unknowns = n / block;
  std::vector<Eigen::Triplet<double>> triplets;
  for (int m = 0; m < system.model_count(); ++m) {
    const Model& model = system.model(m);
    const int offset = system.velocity_offset(m);
    const int size = model.velocity_count();
    const auto qm = q.segment(offset, size);
    // The model's matrices of eq 1.13 at the current state (Terzopoulos surfaces: the matrix
    // from the current tensors, not symmetric for the christoffel normal).
    ModelMatrices matrices;
    model.semi_implicit_matrices(qm, nodal, matrices);
    const SparseMatrix& stiffness = matrices.stiffness;
    append(matrices.mass, offset / block, 1.0 / (dt * dt), triplets);
    append(stiffness, offset / block, 1.0, triplets);
    const bool damped = matrices.damping.nonZeros() > 0;
    if (damped) {
      append(matrices.damping, offset / block, 0.5 / dt, triplets);
    }
    if (nodal) {
      using RowNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
      const Eigen::Map<const RowNodes> velocity(v.data() + offset, size / 3, 3);
      Eigen::Map<RowNodes> b(rhs.data() + offset, size / 3, 3);
      b += (matrices.mass * velocity) / dt;
      if (damped) {
        b -= 0.5 * (matrices.damping * velocity);
      }
    } else {
      rhs.segment(offset, size) += (matrices.mass * v.segment(offset, size)) / dt;
      if (damped) {
        rhs.segment(offset, size) -= 0.5 * (matrices.damping * v.segment(offset, size));
      }
    }
  }

  // Fixed coordinates do not move: identity rows and columns, zero right-hand side.
  std::vector<char> is_fixed(static_cast<size_t>(unknowns), 0);
  for (const int index : fixed) {
    is_fixed[static_cast<size_t>(index / block)] = 1;
    rhs[index] = 0.0;
  }
  if (!fixed.empty()) {
    std::vector<Eigen::Triplet<double>> reduced;
    reduced.reserve(triplets.size());
    for (const auto& entry : triplets) {
      if (!is_fixed[static_cast<size_t>(entry.row())] &&
          !is_fixed[static_cast<size_t>(entry.col())]) {
        reduced.push_back(entry);
      }
    }
    for (int k = 0; k < unknowns; ++k) {
      if (is_fixed[static_cast<size_t>(k)]) {
        reduced.emplace_back(k, k, 1.0);
      }
    }
    triplets.swap(reduced);
  }
  SparseMatrix a(unknowns, unknowns);
  a.setFromTriplets(triplets.begin(), triplets.end());
  a.makeCompressed();
  solver_.compute(a);
  ++factorization_count_;
  if (solver_.info() != Eigen::Success) {
    throw make_error("the semi-implicit matrix M/dt^2 + D/(2dt) + K (", unknowns,
                     " unknowns) could not be factored at t = ", t);
  }
  Eigen::VectorXd increment(n);
  if (nodal) {
    using RowNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
    const Eigen::MatrixXd b = Eigen::Map<const RowNodes>(rhs.data(), unknowns, 3);
    const Eigen::MatrixXd x = solver_.solve(b);
    Eigen::Map<RowNodes>(increment.data(), unknowns, 3) = x;
  } else {
    increment = solver_.solve(rhs);
  }
  for (const int index : fixed) {
    increment[index] = 0.0;
  }
  if (!increment.allFinite()) {
    throw make_error("the semi-implicit step from t = ", t, " with dt = ", dt,
                     " produced a non-finite state; the state is unchanged");
  }
  Eigen::VectorXd q_new = q + increment;
  Eigen::VectorXd v_new = increment / dt;
  system.project_state(q_new, v_new);
  Eigen::VectorXd acceleration = (v_new - v) / dt;
  system.commit_step(q_new, v_new, acceleration, t + dt);
}

}  // namespace dnurbs
