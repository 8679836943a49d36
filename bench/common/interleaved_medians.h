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

/// The median step time of each setup (anything with step()): rounds of one step each until
/// at least `min_repeats` rounds and `budget` seconds per setup, at most `max_repeats` rounds.
template <typename Setup>
std::vector<double> interleaved_medians(std::vector<std::unique_ptr<Setup>>& setups, double budget,
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
  std::vector<double> medians;
  medians.reserve(samples.size());
  for (const auto& s : samples) {
    medians.push_back(median(s));
  }
  return medians;
}

}  // namespace dnurbs::bench
