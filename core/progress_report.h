#pragma once
// Progress of a long computation (a scene run's steps, a fit's iterations, a design's
// evaluations) as the command line shows it: units done of a total, the rate measured since the
// first report, the time left at that rate, and what the caller adds (the simulated time and the
// energy, a fit's distance). On a terminal one line redrawn in place with a bar; elsewhere (a
// log, a pipe) a line every tenth of the total and at the end. Time is measured from the
// report's construction; the overloads that take the elapsed time make what is printed a
// function of the arguments (for tests).

#include <chrono>
#include <ostream>
#include <string>

namespace dnurbs {

/// A duration in seconds as a person reads it: "0.4 s", "12 s", "3 min 20 s", "2 h 05 min".
/// Throws nothing; a negative or non-finite duration is "?".
std::string format_duration(double seconds);

class ProgressReport {
 public:
  /// `unit` names what is counted ("step"); `terminal` selects the redrawn bar.
  ProgressReport(std::ostream& out, std::string unit, bool terminal);

  /// `done` units of `total` (total <= 0: unknown, no percentage and no time left) after
  /// `elapsed_seconds` since the computation started; `detail` is appended ("t = 0.2, energy
  /// 1.5"). Prints when the line changes enough to be worth it (see the file comment).
  void update(long long done, long long total, double elapsed_seconds, const std::string& detail);
  /// update at the time elapsed since the report was made.
  void update(long long done, long long total, const std::string& detail);
  /// Seconds since the report was made (the computation's wall-clock time).
  double elapsed_seconds() const;
  /// Ends a bar left unfinished on a terminal (a run stopped early) with its line break.
  void finish();

  /// The line update would print for these values, without the bar or the line break: "step
  /// 20/200 (10%), 45.2 steps/s, 4 s left; t = 0.2, energy 1.5". The rate and the time left
  /// need two reports (the first one is the baseline) and are left out before.
  std::string line(long long done, long long total, double elapsed_seconds,
                   const std::string& detail) const;

 private:
  std::ostream& out_;
  std::string unit_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  bool has_baseline_ = false;
  long long baseline_done_ = 0;
  double baseline_seconds_ = 0.0;
  int last_percent_ = -1;
  double last_print_seconds_ = 0.0;
  bool bar_open_ = false;
};

}  // namespace dnurbs
