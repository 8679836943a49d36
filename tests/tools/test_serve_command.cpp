// The built `dnurbs serve`: its command line, its refusals (exit 2 for a bad command line, 1 for
// a bad scene or an address it cannot bind), and a clean stop on SIGTERM and SIGINT with the
// loopback address printed first. The protocol is tested in tests/sculpt; a browser drives it
// in tests/web.

#include <csignal>
#include <cstdio>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/tools/run_dnurbs.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using testing::run_dnurbs;

TEST(ServeCommand, HelpNamesEveryOptionAndTheDefaultAddress) {
  const testing::CommandResult help = run_dnurbs("serve --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* option :
       {"--port", "--host", "--out", "--rate", "--resolution", "--web", "127.0.0.1"}) {
    EXPECT_THAT(help.out, HasSubstr(option));
  }
}

TEST(ServeCommand, RefusesBadCommandLinesScenesAndAddresses) {
  const testing::CommandResult port = run_dnurbs("serve --port 70000");
  EXPECT_EQ(port.exit_code, 2);
  EXPECT_THAT(port.err, HasSubstr("--port"));
  EXPECT_EQ(run_dnurbs("serve --rate 0").exit_code, 2);
  EXPECT_EQ(run_dnurbs("serve --bogus").exit_code, 2);
  const testing::CommandResult host = run_dnurbs("serve --port 0 --host not-an-address");
  EXPECT_EQ(host.exit_code, 1);
  EXPECT_THAT(host.err, HasSubstr("host \"not-an-address\" is not an IP address"));
  const testing::CommandResult scene = run_dnurbs("serve /nonexistent/scene.json --port 0");
  EXPECT_EQ(scene.exit_code, 1);
  EXPECT_THAT(scene.err, HasSubstr("/nonexistent/scene.json"));
  const testing::CommandResult web = run_dnurbs("serve --port 0 --web /nonexistent");
  EXPECT_EQ(web.exit_code, 1);
  EXPECT_THAT(web.err, HasSubstr("/nonexistent/index.html is missing"));
}

// Starts the server on a free port, reads its first line, sends `signal` and returns what it
// printed and its exit status.
std::pair<std::string, int> serve_until(int signal) {
  const std::string command =
      "sh -c '" + testing::kDnurbs +
      " serve --port 0 --out /tmp/dnurbs_test_serve_out & pid=$!; sleep 1; kill -" +
      std::to_string(signal) + " $pid; wait $pid; echo \"exit $?\"'";
  FILE* pipe = ::popen(command.c_str(), "r");
  std::string out;
  char buffer[256];
  while (pipe != nullptr && std::fgets(buffer, sizeof(buffer), pipe) != nullptr) {
    out += buffer;
  }
  const int status = pipe == nullptr ? -1 : ::pclose(pipe);
  return {out, status};
}

TEST(ServeCommand, ListensOnLoopbackAndStopsCleanlyOnSigtermAndSigint) {
  for (const int signal : {SIGTERM, SIGINT}) {
    const auto [out, status] = serve_until(signal);
    EXPECT_EQ(status, 0);
    EXPECT_THAT(out, ::testing::StartsWith("dnurbs serve: listening on http://127.0.0.1:"));
    EXPECT_THAT(out, HasSubstr("this machine only"));
    EXPECT_THAT(out, HasSubstr("dnurbs serve: stopped\nexit 0\n")) << "signal " << signal;
  }
}

}  // namespace
}  // namespace dnurbs
