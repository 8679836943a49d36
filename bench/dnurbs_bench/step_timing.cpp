#include "step_timing.h"

#include "bench_support.h"
#include "dnurbs/core/error.h"

namespace dnurbs::bench {

double seconds_per_step(const System& initial, const std::function<void(System&)>& step,
                        double minimum_seconds, int* restarts) {
  System system = initial;
  int count = 0;
  const double seconds = time_per_call(
      [&] {
        try {
          step(system);
        } catch (const Error&) {
          system = initial;
          ++count;
        }
      },
      minimum_seconds);
  if (restarts != nullptr) {
    *restarts = count;
  }
  return seconds;
}

double seconds_per_step(const System& initial, const IntegratorSettings& settings, double dt,
                        double minimum_seconds, int* restarts) {
  Integrator integrator(settings);
  return seconds_per_step(
      initial, [&](System& system) { integrator.step(system, dt); }, minimum_seconds, restarts);
}

}  // namespace dnurbs::bench
