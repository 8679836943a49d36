#include "dnurbs/dynamics/integrators/integrator_scheme.h"

#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs {

IntegratorScheme parse_integrator_scheme(std::string_view name) {
  if (name == "central") {
    return IntegratorScheme::kCentral;
  }
  if (name == "implicit-euler") {
    return IntegratorScheme::kImplicitEuler;
  }
  if (name == "newmark") {
    return IntegratorScheme::kNewmark;
  }
  throw make_error("unknown integrator '", std::string(name),
                   "' (expected central, implicit-euler or newmark)");
}

std::string_view to_string(IntegratorScheme scheme) {
  switch (scheme) {
    case IntegratorScheme::kCentral:
      return "central";
    case IntegratorScheme::kImplicitEuler:
      return "implicit-euler";
    case IntegratorScheme::kNewmark:
      return "newmark";
  }
  return "unknown";
}

StepCoefficients step_coefficients(IntegratorScheme scheme, double newmark_beta,
                                   double newmark_gamma, double t, double dt) {
  StepCoefficients c;
  c.position = dt * dt;
  c.velocity = dt;
  c.store = dt;
  c.force_time = t + dt;
  if (scheme == IntegratorScheme::kNewmark) {
    c.position = newmark_beta * dt * dt;
    c.velocity = newmark_gamma * dt;
    c.store = newmark_gamma * dt;
    c.predictor_acceleration_q = (0.5 - newmark_beta) * dt * dt;
    c.predictor_acceleration_v = (1.0 - newmark_gamma) * dt;
  } else if (scheme == IntegratorScheme::kCentral) {
    c.velocity = 0.5 * dt;  // (q(t+dt) - q(t-dt)) / (2 dt) = v + dt a / 2
    c.force_time = t;
  }
  return c;
}

}  // namespace dnurbs
