// libFuzzer target: the scene reader (parse_scene_json), then the scene writer's round trip.
// Relative file names in a scene resolve against an empty temporary folder, so a shape_file or
// fit.points key reaches the input-file checks (missing file, size, type) without reading
// the fuzzer's surroundings.

#include <filesystem>
#include <string>

#include "core/error.h"
#include "fuzz/fuzz_support.h"
#include "io/scene.h"

namespace {

const std::filesystem::path& empty_folder() {
  static const std::filesystem::path folder = [] {
    auto path = std::filesystem::temp_directory_path() / "dnurbs_fuzz_scene_reader";
    std::filesystem::create_directories(path);
    return path;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = dnurbs::fuzz::input_text(data, size);
  std::string written;
  try {
    written = dnurbs::scene_to_json(dnurbs::parse_scene_json(text, "fuzz.json", empty_folder()));
  } catch (const dnurbs::Error&) {
    return 0;
  }
  dnurbs::fuzz::round_trip_is_fixed_point(
      written, [](const dnurbs::Scene& scene) { return dnurbs::scene_to_json(scene); },
      [](const std::string& json) {
        return dnurbs::parse_scene_json(json, "written.json", empty_folder());
      },
      "scene");
  return 0;
}
