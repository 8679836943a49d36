// ProgressReport: the rate is measured from the first report, the time left follows from it,
// a log gets a line every tenth of the total, a terminal a bar redrawn in place, and without a
// total a line at most once a second.
#include "dnurbs/core/progress_report.h"

#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

TEST(FormatDuration, ReadsAsAPersonWouldSayIt) {
  EXPECT_EQ(format_duration(0.44), "0.4 s");
  EXPECT_EQ(format_duration(9.94), "9.9 s");
  EXPECT_EQ(format_duration(12.4), "12 s");
  EXPECT_EQ(format_duration(200.0), "3 min 20 s");
  EXPECT_EQ(format_duration(3600.0 * 2 + 5 * 60 + 20), "2 h 05 min");
  EXPECT_EQ(format_duration(-1.0), "?");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "?");
  EXPECT_EQ(format_duration(1e300), "> 30 years");
}

TEST(ProgressReport, RateAndTimeLeftComeFromTheRunSinceTheFirstReport) {
  std::ostringstream out;
  ProgressReport progress(out, "step", false);
  // A resumed run: the first report (step 100, 0.5 s in) is the baseline
  progress.update(100, 300, 0.5, "");
  EXPECT_EQ(progress.line(100, 300, 0.5, "t = 1"), "step 100/300 (33%); t = 1");
  // 40 steps in 2 s: 20 steps/s, 160 steps left, 8 s
  EXPECT_EQ(progress.line(140, 300, 2.5, "t = 1.4, energy 0.5"),
            "step 140/300 (46%), 20 steps/s, 8.0 s left; t = 1.4, energy 0.5");
}

TEST(ProgressReport, ALogGetsALineEveryTenthAndTheLast) {
  std::ostringstream out;
  ProgressReport progress(out, "step", false);
  for (int step = 1; step <= 200; ++step) {
    progress.update(step, 200, 0.01 * step, "");
  }
  progress.finish();
  const std::string text = out.str();
  int lines = 0;
  for (const char c : text) {
    lines += c == '\n' ? 1 : 0;
  }
  EXPECT_EQ(lines, 10);  // 10%, 20%, ... 100%: the first tenth is not announced
  EXPECT_NE(text.find("step 20/200 (10%), 100 steps/s, 1.8 s left\n"), std::string::npos);
  EXPECT_TRUE(text.ends_with("\nstep 200/200 (100%), 100 steps/s, 0.0 s left\n"));
  EXPECT_EQ(text.find('\r'), std::string::npos);
}

TEST(ProgressReport, ATerminalGetsABarRedrawnInPlaceAndALineBreakAtTheEnd) {
  std::ostringstream out;
  ProgressReport progress(out, "step", true);
  progress.update(1, 4, 0.1, "");
  progress.update(2, 4, 0.2, "");
  const std::string half = out.str();
  EXPECT_EQ(half.find('\n'), std::string::npos);
  EXPECT_NE(half.find("\r[####################                    ] step 2/4 (50%), 10 steps/s"),
            std::string::npos);
  // A run stopped here gets its line ended by finish, once
  progress.finish();
  progress.finish();
  EXPECT_EQ(out.str(), half + "\n");
}

TEST(ProgressReport, WithoutATotalALineAtMostOnceASecond) {
  std::ostringstream out;
  ProgressReport progress(out, "iteration", false);
  for (int i = 1; i <= 25; ++i) {
    progress.update(i, 0, 0.1 * i, "rms distance 0.1");  // 10 a second for 2.5 s
  }
  EXPECT_EQ(out.str(),
            "iteration 10, 10 iterations/s; rms distance 0.1\n"
            "iteration 20, 10 iterations/s; rms distance 0.1\n");
}

}  // namespace
}  // namespace dnurbs
