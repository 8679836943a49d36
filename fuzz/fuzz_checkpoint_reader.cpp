// libFuzzer target: the checkpoint reader (parse_checkpoint_json) and the writer's round trip,
// which must reproduce every double bit for bit (a resumed run depends on it).

#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/io/checkpoint.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = dnurbs::fuzz::input_text(data, size);
  std::string written;
  try {
    written = dnurbs::checkpoint_to_json(dnurbs::parse_checkpoint_json(text, "fuzz.json"));
  } catch (const dnurbs::Error&) {
    return 0;
  }
  dnurbs::fuzz::round_trip_is_fixed_point(
      written,
      [](const dnurbs::Checkpoint& checkpoint) { return dnurbs::checkpoint_to_json(checkpoint); },
      [](const std::string& json) { return dnurbs::parse_checkpoint_json(json, "written.json"); },
      "checkpoint");
  return 0;
}
