#pragma once
// Seconds per integrator step of a System, the unit of the scaling, machine and needs sections.

#include <functional>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/integrators/integrator.h"

namespace dnurbs::bench {

/// Seconds per step of `step` on a copy of `initial` (after one warm-up step, which factors
/// constant matrices), repeated for at least `minimum_seconds`. A step that throws
/// dnurbs::Error (a free-weight run whose light weight modes blow up) restarts from `initial`;
/// `restarts` counts those.
double seconds_per_step(const System& initial, const std::function<void(System&)>& step,
                        double minimum_seconds, int* restarts = nullptr);

/// seconds_per_step with an Integrator of `settings` and time step dt.
double seconds_per_step(const System& initial, const IntegratorSettings& settings, double dt,
                        double minimum_seconds, int* restarts = nullptr);

}  // namespace dnurbs::bench
