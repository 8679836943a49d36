#pragma once
// A conserving time step for free rigid superquadrics (issue 4: "a scheme you show conserves
// them better" than Newmark for free spin). The Lie-group implicit midpoint rule of the
// Newton-Euler equations about the centre of mass (Euler's equations in the body frame,
// Terzopoulos 2003, eq. 1.38 with M from the rigid mass properties and g = -w x (I w)):
//
//   m (v' - v) / h             = f - alpha m v_m                     v_m = (v + v') / 2
//   x' = x + h v_m                                                   x: centre of mass
//   I (w' - w) / h + w_m x I w_m = tau - alpha I w_m                 w_m = (w + w') / 2
//   R' = R cay(h [w_m]_x),   cay(A) = (I - A/2)^-1 (I + A/2)         quaternion ~ (1, h w_m / 2)
//
// f and tau are the applied forces' resultant and body-frame torque about the centre of mass at
// the midpoint state (time t + h/2). Without forces and damping the scheme conserves exactly (up
// to the Newton tolerance and round-off):
//   - the kinetic energy (1/2) Pi . I^-1 Pi, Pi = I w: a quadratic invariant of Euler's
//     equations, which the implicit midpoint rule conserves;
//   - the spatial angular momentum R Pi: the midpoint equation reads Pi' = cay(-h[w_m]_x) Pi,
//     so R' Pi' = R cay(h[w_m]) cay(-h[w_m]) Pi = R Pi;
//   - the linear momentum m v.
// It is second order and needs one 3 x 3 Newton solve per body and step (no surface integral,
// no sparse factorization). The general Integrator (newmark) remains the scheme for deformable
// models and constraints; this one does not take a solve hook.

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

struct RigidBodyIntegratorSettings {
  /// Newton iterations stop when |delta w'| <= tolerance * max(|w'|, 1e-300), or at round-off
  /// (the update stops shrinking below 1e3 tolerance |w'|); the forces' fixed-point iteration
  /// stops when (v', w') change by less than 1e3 tolerance times their size.
  double tolerance = 1e-15;
  int max_iterations = 50;
};

/// Steps a System whose models are all free rigid bodies (Model::rigid_body: rigid deformable
/// superquadrics with translation and rotation free) and has no fixed coordinates. Rayleigh
/// alpha damping is honoured (beta multiplies K = 0).
class RigidBodyIntegrator {
 public:
  /// Throws Error naming a non-positive tolerance or iteration count.
  explicit RigidBodyIntegrator(RigidBodyIntegratorSettings settings = {});

  /// Advances `system` by dt. Throws Error naming dt if it is not positive and finite, naming the
  /// model if one is not a free rigid body, and (state untouched) if the iteration does
  /// not converge or produces a non-finite state.
  void step(System& system, double dt);

  /// Largest Newton iteration count of the last step.
  int last_iterations() const { return last_iterations_; }

 private:
  RigidBodyIntegratorSettings settings_;
  int last_iterations_ = 0;
};

}  // namespace dnurbs
