#include "dnurbs/io/scene_runner.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

#include "dnurbs/core/error.h"
#include "dnurbs/io/animated_gltf.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/io/cad_file.h"
#include "dnurbs/io/csv_log.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/io/obj_freeform.h"
#include "dnurbs/io/output_path.h"
#include "dnurbs/io/shape_file.h"

namespace dnurbs {
namespace {

std::filesystem::path frame_path(const std::filesystem::path& directory, const SceneOutput& output,
                                 int step) {
  char number[16];
  std::snprintf(number, sizeof(number), "%06d", step);
  std::string name = output.name;
  name += '_';
  name += number;
  name += '.';
  name += output.formats.front();
  return output_file_path(directory / "frames", name);
}

void create_output_directory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw make_error(directory.string(), ": cannot create the output directory: ", error.message());
  }
}

/// Where and how the final outputs are written.
struct FinalOutputPlace {
  const std::filesystem::path& directory;
  int resolution = 0;
  UpAxis up = UpAxis::kZ;
};

/// The final shapes of every model that has an exact one (D-NURBS curves and surfaces).
std::vector<std::pair<int, Shape>> final_shapes(const SceneSimulation& simulation) {
  std::vector<std::pair<int, Shape>> shapes;
  for (int i = 0; i < simulation.system().model_count(); ++i) {
    if (std::optional<Shape> shape = simulation.shape(i)) {
      shapes.emplace_back(i, std::move(*shape));
    }
  }
  return shapes;
}

/// The run's animation, final meshes, CAD file and shape files, as the scene's output asks.
void write_final_outputs(const SceneSimulation& simulation, const FinalOutputPlace& place,
                         const GltfAnimation& animation, SceneRunResult& result) {
  const Scene& scene = simulation.scene();
  const SceneOutput& output = scene.output;
  if (output.animation && animation.frame_count() > 0) {
    result.animation = output_file_path(place.directory, output.name + "_animation.glb");
    animation.write(result.animation);
  }
  if (output.final_mesh) {
    const std::vector<TriangleMesh> meshes = simulation.meshes(place.resolution);
    result.final_meshes.clear();
    for (const std::string& format : output.formats) {
      result.final_meshes.push_back(output_file_path(place.directory, output.name + "." + format));
      export_meshes(meshes, result.final_meshes.back(), place.up);
    }
    result.final_mesh = result.final_meshes.front();
  }
  const std::vector<std::pair<int, Shape>> shapes = final_shapes(simulation);
  if (!output.cad_format.empty() && !shapes.empty()) {
    std::vector<Shape> values;
    values.reserve(shapes.size());
    for (const auto& [model, shape] : shapes) {
      values.push_back(shape);
    }
    const bool obj = output.cad_format == "obj";
    const char* suffix = obj ? "_nurbs.obj" : output.cad_format == "step" ? ".step" : ".igs";
    result.cad_file = output_file_path(place.directory, output.name + suffix);
    if (obj) {
      write_obj_freeform_file(result.cad_file, values);
    } else {
      write_cad_file(result.cad_file, values);
    }
  }
  if (output.shape_files) {
    for (const auto& [model, shape] : shapes) {
      // A model name is any string: one that is not a plain file name becomes model<i>
      const auto path = output_file_path(
          place.directory, output_file_stem(scene.models[static_cast<size_t>(model)].name,
                                            "model" + std::to_string(model)) +
                               ".json");
      write_shape_file(path, shape);
      result.shape_files.push_back(path);
    }
  }
}

}  // namespace

SceneRunResult run_scene(SceneSimulation& simulation, const SceneRunOptions& options,
                         const std::function<void(const SceneRunProgress&)>& progress) {
  const Scene& scene = simulation.scene();
  const SceneOutput& output = scene.output;
  const int resolution = options.resolution > 0 ? options.resolution : output.resolution;
  const std::filesystem::path& directory = options.output_directory;
  const UpAxis up = output.up_axis == "y" ? UpAxis::kY : UpAxis::kZ;
  create_output_directory(directory);
  // Temporaries of a killed earlier run in this folder (io/atomic_write.h)
  remove_stale_temporaries(directory);
  if (output.mesh_every > 0) {
    create_output_directory(directory / "frames");
    remove_stale_temporaries(directory / "frames");
  }

  SceneRunResult result;
  result.total_steps = scene.step_count();
  GltfAnimation animation;
  // A frame in the frame format and, with output.animation, in the animation.
  const auto write_frame = [&](int step) {
    const std::vector<TriangleMesh> meshes = simulation.meshes(resolution);
    export_meshes(meshes, frame_path(directory, output, step), up);
    ++result.frames_written;
    if (output.animation) {
      animation.add_frame(simulation.system().time(), meshes);
    }
  };
  result.log = output_file_path(directory, "log.csv");
  CsvLog log(simulation.log_columns());
  if (options.resume) {
    simulation.restore(read_checkpoint_file(*options.resume), options.resume->string());
    std::ifstream in(result.log, std::ios::binary);
    if (in) {
      std::ostringstream text;
      text << in.rdbuf();
      log.continue_from(text.str(), simulation.steps_done());
    }
  } else {
    log.add_row(0, simulation.log_row(simulation.sample()));
    if (output.mesh_every > 0) {
      write_frame(0);
    }
  }

  const auto write_state = [&]() {
    log.write(result.log);
    result.checkpoint = output_file_path(directory, "checkpoint.json");
    write_checkpoint_file(result.checkpoint, simulation.checkpoint());
  };
  const auto write_final_mesh = [&]() {
    write_final_outputs(simulation, {directory, resolution, up}, animation, result);
  };

  while (simulation.steps_done() < result.total_steps) {
    if (options.stop_after >= 0 && simulation.steps_done() >= options.stop_after) {
      result.stopped = true;
      result.steps_done = simulation.steps_done();
      return result;
    }
    try {
      simulation.step();
    } catch (const SimulationDiverged& error) {
      // The simulation is back at its last good state: keep it
      result.diverged = true;
      result.message = error.what();
      const SceneSample sample = simulation.sample();
      if (log.row_count() == 0 || sample.step % output.log_every != 0) {
        log.add_row(sample.step, simulation.log_row(sample));
      }
      write_state();
      write_final_mesh();
      result.steps_done = simulation.steps_done();
      return result;
    }
    const int step = simulation.steps_done();
    if (step % output.log_every == 0 || step == result.total_steps) {
      log.add_row(step, simulation.log_row(simulation.sample()));
    }
    if (output.mesh_every > 0 && step % output.mesh_every == 0) {
      write_frame(step);
    }
    if (output.checkpoint_every > 0 && step % output.checkpoint_every == 0 &&
        step < result.total_steps) {
      write_state();
    }
    if (progress) {
      const EnergyBudget& budget = simulation.energy_budget();
      progress({step, result.total_steps, simulation.system().time(),
                budget.kinetic_energy() + budget.potential_energy()});
    }
  }
  write_state();
  write_final_mesh();
  result.steps_done = simulation.steps_done();
  return result;
}

}  // namespace dnurbs
