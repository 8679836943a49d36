// libFuzzer target: the shape-file readers, tensor-product (parse_shape_json) and triangular
// (parse_triangular_shape_json), and the OBJ free-form reader (parse_obj_freeform), each
// followed by its writer's round trip. Every reader sees every input: each must refuse the
// others' files with an Error (an OBJ file without curv or surf reads as no shapes).

#include <string>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/io/obj_freeform.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/io/triangular_shape_file.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = dnurbs::fuzz::input_text(data, size);
  try {
    const std::string written = dnurbs::shape_to_json(dnurbs::parse_shape_json(text, "fuzz.json"));
    dnurbs::fuzz::round_trip_is_fixed_point(
        written, [](const dnurbs::Shape& shape) { return dnurbs::shape_to_json(shape); },
        [](const std::string& json) { return dnurbs::parse_shape_json(json, "written.json"); },
        "shape");
  } catch (const dnurbs::Error&) {
  }
  try {
    const std::string written =
        dnurbs::triangular_shape_to_json(dnurbs::parse_triangular_shape_json(text, "fuzz.json"));
    dnurbs::fuzz::round_trip_is_fixed_point(
        written,
        [](const dnurbs::TriangularNurbsSurface& surface) {
          return dnurbs::triangular_shape_to_json(surface);
        },
        [](const std::string& json) {
          return dnurbs::parse_triangular_shape_json(json, "written.json");
        },
        "triangular shape");
  } catch (const dnurbs::Error&) {
  }
  try {
    const std::string written = dnurbs::shapes_to_obj(dnurbs::parse_obj_freeform(text, "fuzz.obj"));
    dnurbs::fuzz::round_trip_is_fixed_point(
        written,
        [](const std::vector<dnurbs::Shape>& shapes) { return dnurbs::shapes_to_obj(shapes); },
        [](const std::string& obj) { return dnurbs::parse_obj_freeform(obj, "written.obj"); },
        "OBJ free-form");
  } catch (const dnurbs::Error&) {
  }
  return 0;
}
