#pragma once
// Runs the built `dnurbs` command for the tools tests and captures what it prints.

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace dnurbs::testing {

inline const std::string kDnurbs = std::string(DNURBS_BINARY_DIR) + "/tools/dnurbs";

/// Exit code (-1 if killed by a signal), whether a signal ended it, stdout and stderr.
struct CommandResult {
  int exit_code = -1;
  bool signalled = false;
  std::string out;
  std::string err;
};

/// An empty scratch directory named after the test and the process.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_tools_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `dnurbs <arguments>` through /bin/sh (arguments as written; stdout is a pipe, not a
/// terminal).
inline CommandResult run_dnurbs(const std::string& arguments) {
  static int counter = 0;
  const auto err_path =
      std::filesystem::temp_directory_path() /
      ("dnurbs_test_tools_stderr_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string command = kDnurbs + " " + arguments + " 2>" + err_path.string();
  CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return result;
  }
  std::array<char, 4096> buffer{};
  size_t read = 0;
  while ((read = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.out.append(buffer.data(), read);
  }
  const int status = ::pclose(pipe);
  result.signalled = WIFSIGNALED(status);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = read_text(err_path);
  std::filesystem::remove(err_path);
  return result;
}

}  // namespace dnurbs::testing
