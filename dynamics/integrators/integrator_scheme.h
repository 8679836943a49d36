#pragma once
// The time-stepping schemes of Integrator (integrator.h) and the coefficients of one step of
// each, in the form every scheme is written in there: the unknown is the step's acceleration a,
//   q_new = q_pred "+" position a,  v_eq = v_pred + velocity a,  v_new = v_store + store a.

#include <string_view>

namespace dnurbs {

enum class IntegratorScheme { kCentral, kImplicitEuler, kNewmark };

/// "central", "implicit-euler" or "newmark"; throws Error naming any other string.
IntegratorScheme parse_integrator_scheme(std::string_view name);
std::string_view to_string(IntegratorScheme scheme);

/// The coefficients of one step from t to t + dt.
struct StepCoefficients {
  double position = 0.0;  ///< q_new = q_pred "+" position a
  double velocity = 0.0;  ///< v_eq = v_pred + velocity a (the velocity in the damping term)
  double store = 0.0;     ///< v_new = v_store + store a
  double force_time = 0.0;
  double predictor_acceleration_q = 0.0;  ///< Newmark: q_pred gets (1/2 - beta) dt^2 a_old
  double predictor_acceleration_v = 0.0;  ///< and v_pred (1 - gamma) dt a_old
};

/// central: Terzopoulos 2003, eq. 1.13 (position dt^2, velocity dt / 2, forces at t);
/// implicit-euler: dt^2 and dt, forces at t + dt; newmark: beta dt^2 and gamma dt, forces at
/// t + dt (newmark_beta and newmark_gamma used by newmark only).
StepCoefficients step_coefficients(IntegratorScheme scheme, double newmark_beta,
                                   double newmark_gamma, double t, double dt);

}  // namespace dnurbs
