#pragma once
// Median seconds of single steps of several setups, taken interleaved (one step of each setup in
// turn) so that a slow phase of the shared machine hits them alike: the timing loop of the step
// benchmarks (bench/springs, bench/free_weights), whose ratios are measured in one run.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

namespace dnurbs::bench {

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

/// The median and the mean step time of each setup.
struct StepTimes {
  std::vector<double> median;
  std::vector<double> mean;
};

/// The step times of each setup (anything with step()): rounds of one step each until at least
/// `min_repeats` rounds and `budget` seconds per setup, at most `max_repeats` rounds. The median
/// resists the shared machine's slow phases; the mean counts the occasional expensive step of a
/// setup whose steps differ (a kept factor replaced now and then), which the median hides.
template <typename Setup>
StepTimes interleaved_times(std::vector<std::unique_ptr<Setup>>& setups, double budget,
                            int min_repeats, int max_repeats) {
  std::vector<std::vector<double>> samples(setups.size());
  double total = 0.0;
  for (int repeat = 0; repeat < max_repeats; ++repeat) {
    if (repeat >= min_repeats && total > budget * static_cast<double>(setups.size())) {
      break;
    }
    for (std::size_t i = 0; i < setups.size(); ++i) {
      const auto start = std::chrono::steady_clock::now();
      setups[i]->step();
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      samples[i].push_back(seconds);
      total += seconds;
    }
  }
  StepTimes times;
  for (const auto& s : samples) {
    times.median.push_back(median(s));
    double sum = 0.0;
    for (const double value : s) {
      sum += value;
    }
    times.mean.push_back(sum / static_cast<double>(s.size()));
  }
  return times;
}

/// The median step time of each setup (interleaved_times).
template <typename Setup>
std::vector<double> interleaved_medians(std::vector<std::unique_ptr<Setup>>& setups, double budget,
                                        int min_repeats, int max_repeats) {
  return interleaved_times(setups, budget, min_repeats, max_repeats).median;
}

}  // namespace dnurbs::bench
