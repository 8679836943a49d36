#pragma once
// The command line of the benchmarks (bench/face_mesh, bench/free_weights, bench/solver,
// bench/springs, bench/terzopoulos): "--quick" and options followed by one value ("--out DIR"),
// read in order, so that a later argument overrides what an earlier one set.

#include <algorithm>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace dnurbs::bench {

/// An option followed by one value: `set` receives the value.
struct ValueOption {
  std::string_view name;
  std::function<void(const char*)> set;
};

/// Reads argv[1], argv[2], ... in order: "--quick" calls `quick`, an option of `options` followed
/// by a value calls its `set`. Returns the first other argument (an option without its value
/// included), where reading stopped, or nothing when every argument was read.
inline std::optional<std::string> read_bench_arguments(int argc, char** argv,
                                                       const std::function<void()>& quick,
                                                       std::initializer_list<ValueOption> options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      quick();
      continue;
    }
    const auto option = std::find_if(options.begin(), options.end(),
                                     [&](const ValueOption& known) { return known.name == arg; });
    if (option == options.end() || i + 1 >= argc) {
      return arg;
    }
    option->set(argv[++i]);
  }
  return std::nullopt;
}

}  // namespace dnurbs::bench
