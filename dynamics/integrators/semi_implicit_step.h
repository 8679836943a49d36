#pragma once
// The semi-implicit step of the grid models as their papers take it: Terzopoulos 2003, eq. 1.13,
//
//   (M/dt^2 + D/(2 dt) + K(q_t)) q_{t+dt} = (2M/dt^2) q_t - (M/dt^2 - D/(2 dt)) q_{t-dt}
//                                           + f(t) + [f_int(q_t) + K(q_t) q_t],
//
// with the matrix built from the current state (Wu & de Melo: the tensors, Christoffel symbols and
// Weingarten coefficients of state k-1 in the matrix that gives state k) and solved sparsely.
// K(q_t) is TerzopoulosSurface::linearized_stiffness (x) I_3 for Terzopoulos surfaces (not
// symmetric for the christoffel normal; the bracket is then zero) and the model's stiffness
// otherwise (the bracket carries an affine model's constant force). q_{t-dt} = q_t - dt v_t.
// It is solved for the increment q_{t+dt} - q_t (so a state at rest stays exactly at rest), with
// one scalar matrix and x, y, z as three right-hand sides when every model is S (x) I_3.
// Fixed coordinates keep their value. The common integrators (dynamics/integrators/integrator.h)
// step the same models through the Model contract instead.

#include <Eigen/SparseLU>

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

class SemiImplicitStepper {
 public:
  /// Advances the system by dt: new coordinates, velocity (q_{t+dt} - q_t)/dt, time t + dt.
  /// Throws Error naming dt if it is not positive and finite, and Error (state unchanged) if the
  /// matrix cannot be factored or the new state is not finite. Models whose velocity count
  /// differs from their coordinate count are rejected by name.
  void step(System& system, double dt);

  /// Factorizations so far (one per step: the matrix depends on the state).
  int factorization_count() const { return factorization_count_; }

 private:
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver_;
  int factorization_count_ = 0;
};

}  // namespace dnurbs
