// call_in_child_process: the child's bytes come back intact, its Error keeps its message, and a
// crash or an early exit in the child is an Error of the caller, not the caller's end.
#include "dnurbs/core/child_process_call.h"

#include <csignal>
#include <cstdlib>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

std::string error_of(const std::function<std::string()>& work, int cpu_seconds = 5) {
  return testing::error_message(
      [&] { call_in_child_process(work, "the test's work", cpu_seconds); });
}

TEST(ChildProcessCall, ReturnsTheChildsBytesIncludingNulsAndMoreThanAPipeHolds) {
  std::string bytes(3 << 20, '\0');  // 3 MiB: many times the 64 kB a pipe buffers
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<char>((i * 7919) % 251);
  }
  EXPECT_EQ(call_in_child_process([&bytes] { return bytes; }, "copy", 5), bytes);
  EXPECT_EQ(call_in_child_process([] { return std::string(); }, "empty", 5), "");
}

TEST(ChildProcessCall, ChildStateChangesDoNotReachTheParent) {
  int counter = 1;
  call_in_child_process(
      [&counter] {
        counter = 2;
        return std::string("done");
      },
      "write", 5);
  EXPECT_EQ(counter, 1);
}

TEST(ChildProcessCall, AnErrorInTheChildKeepsItsMessage) {
  EXPECT_EQ(error_of([]() -> std::string { throw Error("weight 3 is -1, expected > 0"); }),
            "weight 3 is -1, expected > 0");
}

TEST(ChildProcessCall, ACrashInTheChildIsAnErrorNamingTheSignal) {
  EXPECT_EQ(error_of([]() -> std::string {
              std::raise(SIGSEGV);
              return "not reached";
            }),
            "the test's work crashed (signal 11, Segmentation fault)");
  EXPECT_THAT(error_of([]() -> std::string { std::abort(); }),
              ::testing::StartsWith("the test's work crashed (signal 6, "));
}

TEST(ChildProcessCall, AnEarlyExitIsAnErrorWithItsStatus) {
  EXPECT_EQ(error_of([]() -> std::string { std::_Exit(7); }),
            "the test's work ended without a result (exit status 7)");
}

TEST(ChildProcessCall, AnEndlessLoopEndsAtTheCpuTimeLimit) {
  EXPECT_EQ(error_of(
                []() -> std::string {
                  volatile unsigned long spins = 0;
                  for (;;) {
                    spins = spins + 1;
                  }
                },
                1),
            "the test's work did not finish within its 1 s of CPU time");
}

}  // namespace
}  // namespace dnurbs
