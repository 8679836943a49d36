#pragma once
// State checkpoints of a scene run: enough to continue it exactly (time, step count, q, qd and
// the accelerations Newmark carries from step to step), tied to the scene by its state hash.
// JSON with every double written in its exact round-trip form, so that a resumed run repeats
// the uninterrupted one bit for bit.

#include <filesystem>
#include <string>

#include <Eigen/Core>

namespace dnurbs {

struct Checkpoint {
  std::string scene;       ///< the scene file's path (informative)
  std::string scene_hash;  ///< scene_state_hash of the scene it belongs to
  int step = 0;            ///< steps done
  double time = 0.0;
  Eigen::VectorXd coordinates;  ///< q (System::coordinates)
  Eigen::VectorXd velocities;   ///< qd (System::velocities)
  bool accelerations_valid = false;
  Eigen::VectorXd accelerations;  ///< System::accelerations (empty when not valid)
  /// System::flowing_rest_coordinates: the rest shapes that yield (plastic flow), stacked;
  /// empty when none does (then the file has no "rest" key).
  Eigen::VectorXd rest_coordinates;
};

/// The checkpoint as JSON text (doubles with 17 significant digits: they read back exactly).
std::string checkpoint_to_json(const Checkpoint& checkpoint);
/// Parses checkpoint JSON; throws Error "<source>: <json path>: <expected>" when malformed.
Checkpoint parse_checkpoint_json(const std::string& text, const std::string& source = "<string>");
/// Reads / writes (atomically) a checkpoint file; Error naming the file on failure.
Checkpoint read_checkpoint_file(const std::filesystem::path& path);
void write_checkpoint_file(const std::filesystem::path& path, const Checkpoint& checkpoint);

}  // namespace dnurbs
