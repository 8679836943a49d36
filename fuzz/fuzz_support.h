#pragma once
// Shared by the libFuzzer targets of fuzz/: the contract every reader keeps for any input.
//
// A reader either returns a value or throws dnurbs::Error (a message naming the source and the
// JSON path or position). Any other exception escapes LLVMFuzzerTestOneInput, std::terminate
// aborts, and libFuzzer saves the input as a crash: that is the "unexpected error" of the
// command line. A value must survive its own writer: write(parse(text)) parses again and
// writes the same text (round_trip_is_fixed_point), or the target aborts with both texts.

#include <unistd.h>
#include <cstddef>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace dnurbs::fuzz {

/// The fuzzer's bytes as text (any bytes, NUL included: the readers must cope).
inline std::string input_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// An empty folder of the temporary directory, made once per process and removed when it
/// ends: relative file names in a fuzzed scene resolve against it, so a shape_file or
/// fit.points key reaches the input-file checks (missing file, size, type) without reading the
/// fuzzer's surroundings; the mesh target writes its input there.
inline const std::filesystem::path& scratch_folder() {
  struct Folder {
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("dnurbs_fuzz_" + std::to_string(static_cast<long>(getpid())));
    Folder() { std::filesystem::create_directories(path); }
    Folder(const Folder&) = delete;
    Folder& operator=(const Folder&) = delete;
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

/// Aborts (a libFuzzer crash, the input saved) with a message on stderr.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz contract broken: %s\n", what.c_str());
  std::abort();
}

/// Checks that writing, reading back and writing again gives the first text: `write` and
/// `parse` are the pair under test. A parse of written text that throws is a broken contract
/// too (the writer produced something its reader refuses).
template <typename Write, typename Parse>
void round_trip_is_fixed_point(const std::string& written, Write write, Parse parse,
                               const char* what) {
  std::string again;
  try {
    again = write(parse(written));
  } catch (const std::exception& error) {
    fail(std::string(what) + ": written text does not read back: " + error.what() + "\n" + written);
  }
  if (again != written) {
    fail(std::string(what) + ": write(read(write(x))) differs from write(x):\n" + written +
         "\n---\n" + again);
  }
}

}  // namespace dnurbs::fuzz
