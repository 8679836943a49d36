#pragma once
// The command line every example shares: `example_NNN [OUTPUT_DIRECTORY [COUNT]]`, where COUNT
// (frames, or steps for the examples that only write settled shapes) lets the tests in
// examples/CMakeLists.txt run an example small.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

namespace dnurbs::examples {

/// argv[1] (or `fallback` without it) as a directory, created if missing.
inline std::filesystem::path output_directory(int argc, char** argv, const char* fallback) {
  const std::filesystem::path directory = argc > 1 ? argv[1] : fallback;
  std::filesystem::create_directories(directory);
  return directory;
}

/// argv[2] as a positive count (`meaning` names it in messages), or `fallback` without it. Any
/// other value prints a message naming it and exits with status 2.
inline int count_argument(int argc, char** argv, int fallback, const char* meaning) {
  if (argc <= 2) {
    return fallback;
  }
  const std::string text = argv[2];
  std::size_t used = 0;
  int count = 0;
  try {
    count = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || count <= 0) {
    std::fprintf(stderr, "%s: %s must be a positive integer, got '%s'\n", argv[0], meaning,
                 text.c_str());
    std::exit(2);
  }
  return count;
}

}  // namespace dnurbs::examples
