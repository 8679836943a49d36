#pragma once
// Running a scene to its end: steps, the CSV log, mesh frames, checkpoints and the final state,
// every file written atomically (temporary file, then rename) so that a killed run never leaves
// a half-written file. Library code: progress goes to a callback, nothing is printed.
//
// Files in the output directory:
//   log.csv                        step, time, energies, constraint violations, probe positions
//   frames/<name>_<step>.<format>  a mesh of every model every output.mesh_every steps, in the
//                                  first output format
//   checkpoint.json                the state every output.checkpoint_every steps and at the end
//   <name>.<format>                the final meshes (output.final_mesh), in every output format
//   <model name>.json              final D-NURBS shapes as shape files (output.shape_files)

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dnurbs/io/scene_simulation.h"

namespace dnurbs {

struct SceneRunOptions {
  std::filesystem::path output_directory = "dnurbs-out";
  /// Continue from this checkpoint (its log rows up to the checkpoint's step are kept).
  std::optional<std::filesystem::path> resume;
  /// Stop after this many steps in total, writing nothing more (as if the run were killed
  /// there); -1 runs to the end.
  int stop_after = -1;
  /// Overrides output.resolution when > 0.
  int resolution = 0;
};

struct SceneRunProgress {
  int step = 0;   ///< steps done
  int total = 0;  ///< steps of the whole run
  double time = 0.0;
  double energy = 0.0;  ///< kinetic plus elastic energy after the step (log.csv's total_energy)
};

struct SceneRunResult {
  int steps_done = 0;
  int total_steps = 0;
  bool diverged = false;  ///< stopped by a diverging step; the last good state was written
  bool stopped = false;   ///< stopped by stop_after
  std::string message;    ///< the divergence message
  int frames_written = 0;
  std::filesystem::path log;
  std::filesystem::path checkpoint;  ///< empty if none was written
  std::filesystem::path final_mesh;  ///< the first of final_meshes; empty if none was written
  std::vector<std::filesystem::path> final_meshes;  ///< one per output format
  std::vector<std::filesystem::path> shape_files;   ///< final D-NURBS shapes written
  std::filesystem::path cad_file;  ///< the final shapes as NURBS (output.cad_format), or empty
  /// <name>_animation.glb with output.animation, the frames of this run (of a resumed run, the
  /// frames from the resume on); empty if none was written
  std::filesystem::path animation;
};

/// Runs `simulation` (resuming first if asked). Throws Error for unwritable files or a bad
/// checkpoint; a diverging step is not an exception but result.diverged.
SceneRunResult run_scene(SceneSimulation& simulation, const SceneRunOptions& options,
                         const std::function<void(const SceneRunProgress&)>& progress = {});

}  // namespace dnurbs
