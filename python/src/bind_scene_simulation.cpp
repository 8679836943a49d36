// dnurbs.SceneSimulation (io/scene_simulation.h) and dnurbs.run_scene (io/scene_runner.h): a
// scene stepped from Python, its state, samples, meshes and exact shapes as NumPy arrays and
// library objects, and whole runs that write the scene's output files.

#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "dnurbs/io/checkpoint.h"
#include "dnurbs/io/scene_runner.h"
#include "dnurbs/io/scene_simulation.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

py::dict sample_dict(const SceneSample& sample) {
  py::dict result;
  result["step"] = sample.step;
  result["time"] = sample.time;
  result["kinetic_energy"] = sample.kinetic_energy;
  result["potential_energy"] = sample.potential_energy;
  result["violations"] = array_from_vector(sample.violations);
  Eigen::MatrixXd probes(static_cast<Eigen::Index>(sample.probes.size()), 3);
  for (std::size_t i = 0; i < sample.probes.size(); ++i) {
    probes.row(static_cast<Eigen::Index>(i)) = sample.probes[i].transpose();
  }
  result["probes"] = array_from_matrix(probes);
  return result;
}

py::dict run_result_dict(const SceneRunResult& run) {
  return py::dict(py::arg("steps_done") = run.steps_done, py::arg("total_steps") = run.total_steps,
                  py::arg("diverged") = run.diverged, py::arg("stopped") = run.stopped,
                  py::arg("message") = run.message, py::arg("frames_written") = run.frames_written,
                  py::arg("log") = run.log, py::arg("checkpoint") = run.checkpoint,
                  py::arg("final_mesh") = run.final_mesh,
                  py::arg("final_meshes") = run.final_meshes,
                  py::arg("shape_files") = run.shape_files);
}

py::dict cost_dict(const SceneModelCost& cost) {
  return py::dict(
      py::arg("name") = cost.name, py::arg("type") = cost.type,
      py::arg("coordinates") = cost.coordinates, py::arg("velocities") = cost.velocities,
      py::arg("fixed") = cost.fixed, py::arg("constant_matrices") = cost.constant_matrices,
      py::arg("kronecker_block") = cost.kronecker_block,
      py::arg("matrix_non_zeros") = cost.matrix_non_zeros,
      py::arg("factor_non_zeros") = cost.factor_non_zeros, py::arg("solve_work") = cost.solve_work,
      py::arg("automatic_choice") = cost.automatic_choice);
}

// Model i's exact shape as a NurbsCurve or NurbsSurface, or None.
py::object exact_shape(const SceneSimulation& simulation, int i) {
  if (i < 0 || i >= simulation.system().model_count()) {
    throw make_error("model index ", i, " is outside 0..", simulation.system().model_count() - 1);
  }
  const std::optional<Shape> shape = simulation.shape(i);
  if (!shape) {
    return py::none();
  }
  return std::visit([](const auto& value) { return py::cast(value); }, *shape);
}

py::dict simulation_run(SceneSimulation& simulation, const std::filesystem::path& output_directory,
                        const std::optional<std::filesystem::path>& resume, int stop_after,
                        int resolution, const py::object& progress) {
  SceneRunOptions options;
  options.output_directory = output_directory;
  options.resume = resume;
  options.stop_after = stop_after;
  options.resolution = resolution;
  std::function<void(const SceneRunProgress&)> callback;
  if (!progress.is_none()) {
    callback = [&progress](const SceneRunProgress& state) {
      progress(state.step, state.total, state.time, state.energy);
    };
  }
  return run_result_dict(run_scene(simulation, options, callback));
}

void bind_simulation_state(py::class_<SceneSimulation>& simulation) {
  simulation
      .def_property_readonly(
          "time", [](const SceneSimulation& self) { return self.system().time(); },
          "The simulated time.")
      .def_property_readonly("steps_done", &SceneSimulation::steps_done, "Steps done so far.")
      .def_property_readonly(
          "coordinates",
          [](const SceneSimulation& self) {
            return array_from_vector(self.system().coordinates());
          },
          "The stacked coordinates q of every model (System order), shape (n,): a new array "
          "(the state changes with every step).")
      .def_property_readonly(
          "velocities",
          [](const SceneSimulation& self) { return array_from_vector(self.system().velocities()); },
          "The stacked velocities, shape (m,): a new array.")
      .def(
          "model_coordinates",
          [](const SceneSimulation& self, int i) {
            if (i < 0 || i >= self.system().model_count()) {
              throw make_error("model index ", i, " is outside 0..",
                               self.system().model_count() - 1);
            }
            return array_from_vector(self.system().coordinates(i));
          },
          py::arg("model"), "Model `model`'s coordinates, shape (n_i,): a new array.")
      .def(
          "set_coordinates",
          [](SceneSimulation& self, const py::object& q) {
            self.set_coordinates(
                vector_from_array(q, "coordinates", self.system().coordinate_count()));
          },
          py::arg("q"),
          "Sets the stacked coordinates (n,) with zero velocities at the current time.")
      .def(
          "sample", [](const SceneSimulation& self) { return sample_dict(self.sample()); },
          "What the log records now: a dict with step, time, kinetic_energy, "
          "potential_energy, violations (#constraints,) and probes (#probes, 3).")
      .def_property_readonly("log_columns", &SceneSimulation::log_columns,
                             "The column names of the CSV log after 'step'.")
      .def("meshes", &SceneSimulation::meshes, py::arg("resolution") = 24,
           "One TriangleMesh per model at the current state (resolution segments per "
           "direction times the model's resolution scale).")
      .def("shape", &exact_shape, py::arg("model"),
           "Model `model`'s current exact shape: a NurbsCurve, a NurbsSurface or None.")
      .def(
          "checkpoint",
          [](const SceneSimulation& self) { return checkpoint_dict(self.checkpoint()); },
          "The state as a checkpoint dict (as dnurbs.read_checkpoint gives).")
      .def(
          "cost",
          [](const SceneSimulation& self) {
            py::list costs;
            for (const SceneModelCost& cost : self.cost()) {
              costs.append(cost_dict(cost));
            }
            return costs;
          },
          "Per-model sizes and costs at the initial state: a list of dicts.");
}

void bind_simulation_restore(py::class_<SceneSimulation>& simulation) {
  simulation
      .def(
          "restore",
          [](SceneSimulation& self, const py::object& checkpoint) {
            if (py::isinstance<py::dict>(checkpoint)) {
              self.restore(checkpoint_from_dict(checkpoint.cast<py::dict>()), "checkpoint dict");
            } else {
              if (!py::isinstance<py::str>(checkpoint) && !py::hasattr(checkpoint, "__fspath__")) {
                throw py::type_error(
                    "checkpoint is a " +
                    py::str(py::type::of(checkpoint).attr("__name__")).cast<std::string>() +
                    ", must be a dict or a path");
              }
              const auto path = checkpoint.cast<std::filesystem::path>();
              self.restore(read_checkpoint_file(path), path.string());
            }
          },
          py::arg("checkpoint"),
          "Continues from a checkpoint: a dict (SceneSimulation.checkpoint, read_checkpoint) or "
          "a checkpoint file's path. Raises dnurbs.Error if its scene hash or sizes do not "
          "match this scene. Stepping on repeats the uninterrupted run bit for bit.")
      .def(
          "log_row",
          [](const SceneSimulation& self) {
            const std::vector<double> row = self.log_row(self.sample());
            return array_from_vector(Eigen::Map<const Eigen::VectorXd>(
                row.data(), static_cast<Eigen::Index>(row.size())));
          },
          "The CSV log's row of the current state (the values of log_columns), (#columns,).")
      .def_property_readonly(
          "system", [](const SceneSimulation& self) { return System(self.system()); },
          "A copy of the simulation's System (models, forces, springs, state).")
      .def_property_readonly(
          "constraint_descriptions",
          [](const SceneSimulation& self) {
            std::vector<std::string> descriptions;
            descriptions.reserve(static_cast<size_t>(self.constraints().constraint_count()));
            for (int i = 0; i < self.constraints().constraint_count(); ++i) {
              descriptions.push_back(self.constraints().constraint(i).description());
            }
            return descriptions;
          },
          "A description of each of the scene's constraints (a list of str).")
      .def(
          "max_violation",
          [](const SceneSimulation& self) {
            return self.constraints().max_violation(self.system());
          },
          "max_i |C_i| of the scene's constraints at the current state (0 without any).")
      .def_property_readonly(
          "integrator_scheme",
          [](const SceneSimulation& self) {
            return std::string(to_string(self.integrator().settings().scheme));
          },
          "The scene's integration scheme: central, implicit-euler or newmark.")
      .def(
          "energy_budget",
          [](const SceneSimulation& self) {
            const EnergyBudget& budget = self.energy_budget();
            return py::dict(py::arg("initial_energy") = budget.initial_energy(),
                            py::arg("work") = budget.work(),
                            py::arg("energy_moved") = budget.energy_moved());
          },
          "The run's energy budget: a dict initial_energy, work (of the applied forces so far), "
          "energy_moved.");
}

}  // namespace

void bind_scene_simulation(py::module_& module) {
  py::class_<SceneSimulation> simulation(
      module, "SceneSimulation",
      "A scene turned into a running simulation (the System of its models, forces, "
      "constraints and integrator). step() advances it; the state reads as NumPy arrays.");
  simulation
      .def(py::init<Scene>(), py::arg("scene"),
           "Runs the scene's pending fits and builds the simulation; raises dnurbs.Error "
           "'<source>: <json path>: <problem>' when the library rejects a part of the scene.")
      .def_property_readonly("scene", &SceneSimulation::scene, "The Scene.")
      .def(
          "step",
          [](SceneSimulation& self, int count) {
            if (count < 0) {
              throw make_error("step count ", count, " is negative");
            }
            for (int i = 0; i < count; ++i) {
              self.step();
            }
          },
          py::arg("count") = 1,
          "Advances `count` time steps of dt. Raises dnurbs.SimulationDiverged (the state back "
          "at the last good step) if a step diverges.")
      .def("run", &simulation_run, py::arg("output_directory"), py::arg("resume") = py::none(),
           py::arg("stop_after") = -1, py::arg("resolution") = 0, py::arg("progress") = py::none(),
           "Runs the scene to its end as `dnurbs run` does, writing log.csv, frames/, "
           "checkpoint.json, the final meshes and shape files into `output_directory`. resume: "
           "a checkpoint file to continue from; stop_after: stop after this many steps in "
           "total (-1: run to the end); resolution > 0 overrides the mesh resolution; "
           "progress(step, total, time, energy) is called after each step (energy: kinetic plus "
           "elastic, log.csv's total_energy). Returns a dict (steps_done, total_steps, diverged, "
           "stopped, message, frames_written, log, checkpoint, final_mesh, final_meshes (one per "
           "output format), shape_files); a diverging step is not an exception here.");
  bind_simulation_state(simulation);
  bind_simulation_restore(simulation);
}

}  // namespace dnurbs::python
