// libFuzzer target: the scene reader (parse_scene_json), then the scene writer's round trip.
// Relative file names resolve against an empty folder (fuzz::scratch_folder).

#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = dnurbs::fuzz::input_text(data, size);
  std::string written;
  try {
    written = dnurbs::scene_to_json(
        dnurbs::parse_scene_json(text, "fuzz.json", dnurbs::fuzz::scratch_folder()));
  } catch (const dnurbs::Error&) {
    return 0;
  }
  dnurbs::fuzz::round_trip_is_fixed_point(
      written, [](const dnurbs::Scene& scene) { return dnurbs::scene_to_json(scene); },
      [](const std::string& json) {
        return dnurbs::parse_scene_json(json, "written.json", dnurbs::fuzz::scratch_folder());
      },
      "scene");
  return 0;
}
