#pragma once
// Scene files (docs/scene-format.md): one JSON document that describes a simulation — models
// and their materials and boundary conditions, applied forces with time schedules, constraints
// with their Baumgarte parameters, the integrator, the run length, probes (logged to CSV) and
// outputs. The Scene struct is the parsed file; scene_to_json writes it back so that
// parse(write(parse(text))) == parse(text) for every key.
//
// This file is the dispatcher: the keys of each model, force and constraint type are read and
// written by that type (io/scene_registry.h, io/models/, io/scene_forces.h,
// io/scene_constraints.h). Model references (`"model": 0` or `"model": "sheet"`) are resolved to
// indices when parsing; the writer writes indices. A model whose initial shape is fitted to
// points ("fit") is parsed without running the fit: io/scene_fit.h fit_initial_shapes does that.

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/io/clone_ptr.h"
#include "dnurbs/io/scene_obstacles.h"
#include "dnurbs/io/scene_spec.h"
#include "dnurbs/io/schedule.h"

namespace dnurbs {

/// Fixed control points / nodes and clamped borders. JSON key "boundary".
struct SceneBoundary {
  bool clamp_border = false;      ///< models with a border (Model::fix_border)
  std::vector<int> fixed_points;  ///< control points (D-NURBS) or nodes (grids, snakes)
  /// >= 0: local sculpting (Model::freeze_outside), the control points outside the support of
  /// the model's forces and constraints grown by this many rings are fixed; -1: off
  int local_sculpting_margin = -1;
  bool operator==(const SceneBoundary&) const = default;
};

/// One model of the scene: its name, its type's keys (`spec`), its boundary conditions and
/// the resolution of its meshes.
struct SceneModel {
  std::string name;
  ClonePtr<SceneModelSpec> spec;
  SceneBoundary boundary;
  /// Mesh segments per direction = round(scale * output resolution) (at least 3).
  Eigen::Vector2d resolution_scale = Eigen::Vector2d::Ones();
};
/// The model's "type" string.
std::string scene_model_type(const SceneModel& model);

/// An applied force (its type's keys in `spec`), acting while start <= t < end.
struct SceneForce {
  ClonePtr<SceneForceSpec> spec;
  double start = 0.0;
  double end = std::numeric_limits<double>::infinity();
};

/// A constraint (its type's keys in `spec`) with its Baumgarte parameters.
struct SceneConstraint {
  ClonePtr<SceneConstraintSpec> spec;
  double alpha = 20.0;
  double beta = -1.0;  ///< < 0: beta = alpha (critical damping)
};

struct SceneIntegrator {
  std::string scheme = "newmark";  ///< "central", "implicit-euler", "newmark"
  double dt = 0.01;
  int newton_iterations = 0;
  double newton_tolerance = 1e-12;
  /// IntegratorSettings::automatic_newton: Newton iterations for free-weight D-NURBS even with
  /// newton_iterations = 0.
  bool automatic_newton = true;
  /// IntegratorSettings::keep_factor_across_steps: the automatic Newton starts each step from the
  /// factor the last step ended with.
  bool keep_factor_across_steps = true;
  double newmark_beta = 0.25;
  double newmark_gamma = 0.5;
  /// The run stops as diverged when its energy (kinetic + elastic + springs) exceeds this.
  double max_energy = 1e12;
  /// ... or when it exceeds the energy budget (initial energy plus the forces' work) by more
  /// than this times the energy the run has moved (dynamics/integrators/energy_budget.h).
  double energy_growth = 1.0;
  bool operator==(const SceneIntegrator&) const = default;
};

/// A material point whose position is logged.
struct SceneProbe {
  std::string name;
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  bool operator==(const SceneProbe&) const = default;
};

struct SceneOutput {
  int mesh_every = 0;  ///< a mesh every N steps (0: none but the final one)
  /// Mesh formats, distinct, of obj, stl, ply, gltf, glb: the final mesh is written in each,
  /// frames in the first; the preview renders the first.
  std::vector<std::string> formats = {"obj"};
  /// The up axis of OBJ, STL and PLY meshes: "z" (dnurbs' own) or "y" (io/mesh_up_axis.h); glTF
  /// is always Y-up.
  std::string up_axis = "z";
  int resolution = 24;  ///< mesh segments per direction
  bool final_mesh = true;
  bool preview = false;  ///< PNG of the final mesh (the tool renders it)
  /// The frames (mesh_every > 0) also as one animated glTF, <name>_animation.glb
  /// (io/animated_gltf.h)
  bool animation = false;
  int log_every = 1;           ///< CSV rows every N steps (and the last step)
  int checkpoint_every = 0;    ///< checkpoint.json every N steps (0: only the final state)
  std::string name = "scene";  ///< file stem of the final mesh, preview
  bool shape_files = false;    ///< the final exact shapes as shape files <model name>.json
  /// The final exact shapes of every model together as NURBS in one CAD file: "" (none), "step"
  /// (<name>.step), "iges" (<name>.igs) or "obj" (free-form geometry, <name>_nurbs.obj)
  std::string cad_format;
  bool operator==(const SceneOutput&) const = default;
};

/// Static design settings ("design", design/energy_minimization.h DesignSettings): `dnurbs design`
/// minimizes the models' elastic energy minus the work of the forces at time 0, subject to the
/// constraints as equalities, instead of running the dynamics (`dnurbs run` ignores it).
struct SceneDesign {
  std::string algorithm = "slsqp";  ///< "slsqp" or "auglag_lbfgs"
  double variable_tolerance = 1e-14;
  double energy_tolerance = 0.0;
  double constraint_tolerance = 1e-12;
  int max_evaluations = 5000;
  double max_seconds = 0.0;  ///< 0: no limit
  bool operator==(const SceneDesign&) const = default;
};

struct Scene {
  std::string source = "<string>";  ///< file name (messages); not written
  std::filesystem::path directory;  ///< relative file names resolve here; not written
  /// "<file>=<content hash>" of every data file the scene read (shape files, images, points;
  /// SceneReader::input_digests); not written, but part of the state hash
  std::vector<std::string> input_digests;
  std::string description;
  std::vector<SceneModel> models;
  std::vector<SceneForce> forces;
  std::vector<SceneConstraint> constraints;
  SceneIntegrator integrator;
  int steps = 0;          ///< run length in steps ("run": {"steps": N}) ...
  double duration = 0.0;  ///< ... or in time ("run": {"duration": T}); exactly one is set
  /// ... or in frames of sub-steps ("run": {"frames": F, "frame_rate": R, "substeps": N}; Romero
  /// 2005, section 4.3: the solver advances each frame of 1/R in steps): steps = F N and
  /// integrator.dt = 1 / (R N), and output.log_every and output.mesh_every default to N (a log
  /// row and a mesh per frame). 0 when the run is given in steps or duration.
  double frame_rate = 0.0;
  int substeps = 0;
  int frames = 0;
  std::vector<SceneProbe> probes;
  SceneOutput output;
  std::optional<SceneDesign> design;  ///< present if the scene has a "design" section
  /// Rigid obstacles (keys "obstacles" and "contact", io/scene_obstacles.h) every model meets.
  std::vector<Obstacle> obstacles;
  SceneContact contact;
  /// The number of steps to run: steps, or ceil(duration / dt - 1e-9).
  int step_count() const;
};

/// Scenes (and their parts) compare by what they write: equal JSON, equal scenes.
bool operator==(const SceneModel& a, const SceneModel& b);
bool operator==(const SceneForce& a, const SceneForce& b);
bool operator==(const SceneConstraint& a, const SceneConstraint& b);
bool operator==(const Scene& a, const Scene& b);

/// Parses scene JSON. `source` names the text in messages; relative file names resolve against
/// `directory`. Throws Error "<source>: <json path>: <what was expected>" for every malformed
/// key (unparseable JSON with line and column, missing, unknown or mistyped keys, values out of
/// range, unknown model names or indices, bad shapes). Runs no fit.
Scene parse_scene_json(const std::string& text, const std::string& source = "<string>",
                       const std::filesystem::path& directory = {});
/// Reads a scene file (Error naming the file if it cannot be read).
Scene read_scene_file(const std::filesystem::path& path);
/// The scene as JSON text (every key; numbers round-trip exactly).
std::string scene_to_json(const Scene& scene);
/// A hash (16 hex digits, FNV-1a 64) of everything that determines the simulated state: the
/// scene without "output" and "description", and the content of the data files it read
/// (input_digests), so that an edited image or point file changes it. Checkpoints carry it.
std::string scene_state_hash(const Scene& scene);

}  // namespace dnurbs
