// Shape files (io/shape_file.h: NURBS curves and surfaces; io/triangular_shape_file.h: triangular
// NURBS surfaces), CAD files (io/cad_file.h: STEP and IGES) and checkpoint files
// (io/checkpoint.h) read and written from Python.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "dnurbs/io/cad_file.h"
#include "dnurbs/io/checkpoint.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/obj_freeform.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/io/shape_recipe.h"
#include "dnurbs/io/triangular_shape_file.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

py::object shape_object(const Shape& shape) {
  return std::visit([](const auto& value) { return py::cast(value); }, shape);
}

// A NurbsCurve or NurbsSurface argument as a Shape; TypeError naming the type otherwise.
Shape shape_argument(const py::object& value) {
  if (py::isinstance<NurbsCurve>(value)) {
    return value.cast<NurbsCurve>();
  }
  if (py::isinstance<NurbsSurface>(value)) {
    return value.cast<NurbsSurface>();
  }
  throw py::type_error("shape is a " + std::string(py::str(py::type::of(value).attr("__name__"))) +
                       ", must be a NurbsCurve or a NurbsSurface");
}

py::list shape_list(const std::vector<Shape>& shapes) {
  py::list list;
  for (const Shape& shape : shapes) {
    list.append(shape_object(shape));
  }
  return list;
}

std::vector<Shape> shape_arguments(const py::iterable& shapes) {
  std::vector<Shape> values;
  for (const py::handle shape : shapes) {
    values.push_back(shape_argument(py::reinterpret_borrow<py::object>(shape)));
  }
  return values;
}

}  // namespace

Checkpoint checkpoint_from_dict(const py::dict& values) {
  const auto entry = [&values](const char* key) -> py::object {
    if (!values.contains(key)) {
      throw make_error("checkpoint has no \"", key, "\"");
    }
    return values[key];
  };
  Checkpoint checkpoint;
  checkpoint.scene = entry("scene").cast<std::string>();
  checkpoint.scene_hash = entry("scene_hash").cast<std::string>();
  checkpoint.step = entry("step").cast<int>();
  checkpoint.time = entry("time").cast<double>();
  checkpoint.coordinates = vector_from_array(entry("coordinates"), "coordinates");
  checkpoint.velocities = vector_from_array(entry("velocities"), "velocities");
  checkpoint.accelerations_valid = entry("accelerations_valid").cast<bool>();
  checkpoint.accelerations = vector_from_array(entry("accelerations"), "accelerations");
  if (values.contains("rest_coordinates")) {
    checkpoint.rest_coordinates = vector_from_array(values["rest_coordinates"], "rest_coordinates");
  }
  return checkpoint;
}

void bind_shape_files(py::module_& module) {
  module.def(
      "parse_shape",
      [](const std::string& text, const std::string& source) {
        return shape_object(parse_shape_json(text, source));
      },
      py::arg("text"), py::arg("source") = "<string>",
      "A NurbsCurve or NurbsSurface from shape JSON text; raises dnurbs.Error '<source>: <json "
      "path>: <what was expected>'.");
  module.def(
      "make_shape",
      [](const std::string& recipe, const std::filesystem::path& directory) {
        const SceneReader reader("recipe", directory);
        return shape_object(make_shape(reader, parse_json_document(recipe, "recipe"), ""));
      },
      py::arg("recipe"), py::arg("directory") = std::filesystem::path("."),
      "The shape of a shape recipe, JSON text such as '{\"kind\": \"plane\", \"size\": [3, 3]}' "
      "(docs/scene-format.md, Generated shapes; shape file names resolve in `directory`); raises "
      "dnurbs.Error 'recipe: <json path>: <what was expected>'.");
  module.def(
      "read_shape",
      [](const std::filesystem::path& path) { return shape_object(read_shape_file(path)); },
      py::arg("path"), "Reads a shape file (a NurbsCurve or NurbsSurface).");
  module.def(
      "shape_to_json", [](const py::object& shape) { return shape_to_json(shape_argument(shape)); },
      py::arg("shape"),
      "A NurbsCurve or NurbsSurface as shape JSON text (numbers round-trip exactly).");
  module.def(
      "write_shape",
      [](const std::filesystem::path& path, const py::object& shape) {
        write_shape_file(path, shape_argument(shape));
      },
      py::arg("path"), py::arg("shape"),
      "Writes a NurbsCurve or NurbsSurface to a shape file (atomically).");
  module.def("cad_exchange_available", &cad_exchange_available,
             "True if this dnurbs reads and writes STEP and IGES (built with Open CASCADE).");
  module.def(
      "read_cad_file",
      [](const std::filesystem::path& path) { return shape_list(read_cad_file(path)); },
      py::arg("path"),
      "The NurbsCurves and NurbsSurfaces of a STEP (.step, .stp) or IGES (.iges, .igs) file, in "
      "the file's order (STEP: faces, then free edges); raises dnurbs.Error naming a trimmed face "
      "or an entity with no exact NURBS form.");
  module.def(
      "write_cad_file",
      [](const std::filesystem::path& path, const py::iterable& shapes) {
        write_cad_file(path, shape_arguments(shapes));
      },
      py::arg("path"), py::arg("shapes"),
      "Writes NurbsCurves and NurbsSurfaces to a STEP or IGES file by its extension (17-digit "
      "numbers: read_cad_file gives them back exactly, periodic ones periodic).");
  module.def(
      "read_obj_freeform",
      [](const std::filesystem::path& path) { return shape_list(read_obj_freeform_file(path)); },
      py::arg("path"),
      "The NurbsCurves and NurbsSurfaces of an OBJ file's free-form curv and surf statements, in "
      "file order (meshes in the file are ignored); raises dnurbs.Error '<path>: line L: ...'.");
  module.def(
      "write_obj_freeform",
      [](const std::filesystem::path& path, const py::iterable& shapes) {
        write_obj_freeform_file(path, shape_arguments(shapes));
      },
      py::arg("path"), py::arg("shapes"),
      "Writes NurbsCurves and NurbsSurfaces as OBJ free-form geometry (exact numbers; periodic "
      "ones in open form, read back periodic).");
  module.def("parse_triangular_shape", &parse_triangular_shape_json, py::arg("text"),
             py::arg("source") = "<string>",
             "A TriangularNurbsSurface from triangular_nurbs shape JSON text.");
  module.def("read_triangular_shape", &read_triangular_shape_file, py::arg("path"),
             "Reads a triangular_nurbs shape file.");
  module.def("triangular_shape_to_json", &triangular_shape_to_json, py::arg("surface"),
             "A TriangularNurbsSurface as JSON text (knot clouds included; exact numbers).");
  module.def("write_triangular_shape", &write_triangular_shape_file, py::arg("path"),
             py::arg("surface"), "Writes a TriangularNurbsSurface to a shape file (atomically).");
  module.def("is_triangular_shape_file", &is_triangular_shape_file, py::arg("path"),
             "True if the file holds a JSON object of type triangular_nurbs.");
  module.def(
      "write_checkpoint",
      [](const std::filesystem::path& path, const py::dict& checkpoint) {
        write_checkpoint_file(path, checkpoint_from_dict(checkpoint));
      },
      py::arg("path"), py::arg("checkpoint"),
      "Writes a checkpoint dict (as SceneSimulation.checkpoint gives) to a file, every number "
      "exact.");
  module.def(
      "parse_checkpoint",
      [](const std::string& text, const std::string& source) {
        return checkpoint_dict(parse_checkpoint_json(text, source));
      },
      py::arg("text"), py::arg("source") = "<string>", "A checkpoint dict from JSON text.");
  module.def(
      "checkpoint_to_json",
      [](const py::dict& checkpoint) {
        return checkpoint_to_json(checkpoint_from_dict(checkpoint));
      },
      py::arg("checkpoint"), "A checkpoint dict as JSON text (17 significant digits).");
}

}  // namespace dnurbs::python
