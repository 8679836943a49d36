#include "dnurbs/core/progress_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

namespace dnurbs {

namespace {

// Without a known total a line is printed at most this often (seconds): a fit or a design
// shows it is alive after a second and does not flood a log.
constexpr double kUnknownTotalInterval = 1.0;
constexpr int kBarWidth = 40;

std::string two_digits(long long value) {
  char text[24];
  std::snprintf(text, sizeof text, "%02lld", value);
  return text;
}

}  // namespace

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) {
    return "?";
  }
  if (seconds < 10.0) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", seconds);
    return text;
  }
  if (seconds > 1e9) {  // beyond any run worth waiting for, and beyond long long minutes
    return "> 30 years";
  }
  const auto whole = static_cast<long long>(std::llround(seconds));
  if (whole < 60) {
    return std::to_string(whole) + " s";
  }
  if (whole < 3600) {
    return std::to_string(whole / 60) + " min " + two_digits(whole % 60) + " s";
  }
  return std::to_string(whole / 3600) + " h " + two_digits(whole % 3600 / 60) + " min";
}

ProgressReport::ProgressReport(std::ostream& out, std::string unit, bool terminal)
    : out_(out), unit_(std::move(unit)), terminal_(terminal) {}

std::string ProgressReport::line(long long done, long long total, double elapsed_seconds,
                                 const std::string& detail) const {
  std::ostringstream text;
  text << unit_ << " " << done;
  if (total > 0) {
    text << "/" << total << " (" << 100 * done / total << "%)";
  }
  const double span = elapsed_seconds - baseline_seconds_;
  if (has_baseline_ && done > baseline_done_ && span > 0.0) {
    const double rate = static_cast<double>(done - baseline_done_) / span;
    text.precision(3);
    text << ", " << rate << " " << unit_ << "s/s";
    if (total > 0) {
      text << ", " << format_duration(static_cast<double>(total - done) / rate) << " left";
    }
  }
  if (!detail.empty()) {
    text << "; " << detail;
  }
  return text.str();
}

void ProgressReport::update(long long done, long long total, double elapsed_seconds,
                            const std::string& detail) {
  if (!has_baseline_) {
    has_baseline_ = true;
    baseline_done_ = done;
    baseline_seconds_ = elapsed_seconds;
  }
  const bool last = total > 0 && done >= total;
  bool print = last;
  int percent = -1;
  if (total > 0) {
    percent = static_cast<int>(100 * done / total);
    // A redrawn bar follows every percent, a log every tenth
    print = print || (terminal_ ? percent != last_percent_ : percent / 10 != last_percent_ / 10);
  } else {
    const double interval = terminal_ ? kUnknownTotalInterval / 10 : kUnknownTotalInterval;
    print = elapsed_seconds - last_print_seconds_ >= interval;
  }
  if (!print) {
    return;
  }
  last_percent_ = percent;
  last_print_seconds_ = elapsed_seconds;
  const std::string text = line(done, total, elapsed_seconds, detail);
  if (!terminal_) {
    out_ << text << "\n" << std::flush;
    return;
  }
  out_ << "\r";
  if (total > 0) {
    const int filled = percent * kBarWidth / 100;
    out_ << "[" << std::string(static_cast<size_t>(filled), '#')
         << std::string(static_cast<size_t>(kBarWidth - filled), ' ') << "] ";
  }
  // Clear what a longer previous line left at the end
  out_ << text << "\033[K";
  bar_open_ = !last;
  out_ << (last ? "\n" : "") << std::flush;
}

void ProgressReport::update(long long done, long long total, const std::string& detail) {
  update(done, total, elapsed_seconds(), detail);
}

double ProgressReport::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressReport::finish() {
  if (bar_open_) {
    out_ << "\n" << std::flush;
    bar_open_ = false;
  }
}

}  // namespace dnurbs
