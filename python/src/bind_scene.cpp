// dnurbs.Scene (io/scene.h): scene files read, parsed and written back, and checkpoints
// (io/checkpoint.h) as dicts of arrays.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "dnurbs/io/checkpoint.h"
#include "dnurbs/io/scene.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

py::dict checkpoint_dict(const Checkpoint& checkpoint) {
  py::dict result;
  result["scene"] = checkpoint.scene;
  result["scene_hash"] = checkpoint.scene_hash;
  result["step"] = checkpoint.step;
  result["time"] = checkpoint.time;
  result["coordinates"] = array_from_vector(checkpoint.coordinates);
  result["velocities"] = array_from_vector(checkpoint.velocities);
  result["accelerations_valid"] = checkpoint.accelerations_valid;
  result["accelerations"] = array_from_vector(checkpoint.accelerations);
  result["rest_coordinates"] = array_from_vector(checkpoint.rest_coordinates);
  return result;
}

void bind_scene(py::module_& module) {
  py::class_<Scene>(
      module, "Scene",
      "A parsed scene file (docs/scene-format.md): models, forces, constraints, integrator, run "
      "length, probes and outputs. Read one with dnurbs.read_scene or dnurbs.parse_scene, run "
      "it with dnurbs.SceneSimulation.")
      .def_readonly("source", &Scene::source, "The file name (in messages).")
      .def_readonly("description", &Scene::description, "The scene's description.")
      .def_property_readonly("step_count", &Scene::step_count,
                             "The number of steps of the run (steps, or duration / dt).")
      .def_property_readonly(
          "dt", [](const Scene& self) { return self.integrator.dt; }, "The time step.")
      .def_property_readonly(
          "scheme", [](const Scene& self) { return self.integrator.scheme; },
          "The integrator: central, implicit-euler or newmark.")
      .def_property_readonly(
          "model_names",
          [](const Scene& self) {
            std::vector<std::string> names;
            for (const SceneModel& model : self.models) {
              names.push_back(model.name);
            }
            return names;
          },
          "The names of the models, in System order.")
      .def_property_readonly(
          "model_types",
          [](const Scene& self) {
            std::vector<std::string> types;
            for (const SceneModel& model : self.models) {
              types.push_back(scene_model_type(model));
            }
            return types;
          },
          "The type strings of the models (dnurbs_curve, dnurbs_surface, ...).")
      .def("to_json", &scene_to_json, "The scene as JSON text (every key; exact numbers).")
      .def("state_hash", &scene_state_hash,
           "The hash (16 hex digits) of what determines the simulated state.")
      .def("__eq__", [](const Scene& a, const Scene& b) { return a == b; });

  module.def("read_scene", &read_scene_file, py::arg("path"),
             "Reads and parses a scene file (a Scene); relative file names in it resolve "
             "against its folder. Raises dnurbs.Error '<file>: <json path>: <problem>'.");
  module.def("parse_scene", &parse_scene_json, py::arg("text"), py::arg("source") = "<string>",
             py::arg("directory") = std::filesystem::path(),
             "Parses scene JSON text; `source` names it in messages, `directory` resolves "
             "relative file names.");
  module.def(
      "read_checkpoint",
      [](const std::filesystem::path& path) { return checkpoint_dict(read_checkpoint_file(path)); },
      py::arg("path"),
      "Reads a checkpoint file: a dict with scene, scene_hash, step, time, coordinates (n,), "
      "velocities (m,), accelerations_valid and accelerations (m,) or (0,).");
}

}  // namespace dnurbs::python
