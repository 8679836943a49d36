#include "dnurbs/vision/topology_adaptive_parameters.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

void check_parameter(const char* model, double value, const char* name, bool positive) {
  if (!std::isfinite(value) || value < 0.0 || (positive && value == 0.0)) {
    throw make_error(model, " ", name, " = ", value, positive ? " is not > 0" : " is not >= 0",
                     " and finite");
  }
}

}  // namespace

void TopologyAdaptiveParameters::validate(const char* model, double tension_eigenvalue,
                                          double rigidity_eigenvalue) const {
  check_parameter(model, cell_size, "cell_size", true);
  check_parameter(model, tension, "tension", false);
  check_parameter(model, rigidity, "rigidity", false);
  check_parameter(model, damping, "damping", true);
  check_parameter(model, time_step, "time_step", true);
  check_parameter(model, inflation, "inflation", false);
  check_parameter(model, inflation_band, "inflation_band", false);
  check_parameter(model, edge_weight, "edge_weight", false);
  if (!std::isfinite(threshold)) {
    throw make_error(model, " threshold = ", threshold, " is not finite");
  }
  if (steps_per_reparameterization < 1) {
    throw make_error(model, " steps_per_reparameterization = ", steps_per_reparameterization,
                     " is not >= 1");
  }
  // Explicit Euler is stable while the step times the stiffest mode stays below 1.
  const double stiffness =
      time_step / damping * (tension_eigenvalue * tension + rigidity_eigenvalue * rigidity);
  if (stiffness >= 1.0) {
    throw make_error(model, " explicit step is unstable: time_step / damping (", tension_eigenvalue,
                     " tension + ", rigidity_eigenvalue, " rigidity) = ", stiffness,
                     ", must be < 1");
  }
}

double inflation_switch(double intensity, double threshold, double band) {
  if (band == 0.0) {
    return intensity >= threshold ? 1.0 : -1.0;
  }
  return std::clamp((intensity - threshold) / band, -1.0, 1.0);
}

}  // namespace dnurbs
