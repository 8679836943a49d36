#pragma once
// Scene files (docs/scene-format.md): one JSON document that describes a simulation — models
// and their materials and boundary conditions, applied forces with time schedules, constraints
// with their Baumgarte parameters, the integrator, the run length, probes (logged to CSV) and
// outputs. The Scene struct is the parsed file; scene_to_json writes it back so that
// parse(write(parse(text))) == parse(text) for every key.
//
// Model references (`"model": 0` or `"model": "sheet"`) are resolved to indices when parsing;
// the writer writes indices.

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "io/shape_file.h"

namespace dnurbs {

/// A 3-vector that is a constant or keyframed in time (natural cubic spline through the
/// keyframes, constant before the first and after the last: TargetTrajectory::keyframes).
/// JSON: `[x, y, z]` or `{"times": [t0, t1, ...], "values": [[x, y, z], ...]}`.
struct VectorSchedule {
  std::vector<double> times;            ///< empty for a constant
  std::vector<Eigen::Vector3d> values;  ///< one value (constant) or one per time
  /// The value at time t.
  Eigen::Vector3d at(double time) const;
  bool operator==(const VectorSchedule&) const = default;
};

/// A scalar that is a constant or keyframed in time (as VectorSchedule).
/// JSON: `p` or `{"times": [...], "values": [...]}`.
struct ScalarSchedule {
  std::vector<double> times;
  std::vector<double> values;
  double at(double time) const;
  bool operator==(const ScalarSchedule&) const = default;
};

/// Fixed control points / nodes and clamped borders. JSON key "boundary".
struct SceneBoundary {
  bool clamp_border = false;      ///< D-NURBS surfaces and Terzopoulos surfaces only
  std::vector<int> fixed_points;  ///< control points (D-NURBS) or nodes (grids, snakes)
  /// D-NURBS only, >= 0: local sculpting (dynamics/dnurbs/local_sculpting.h), the control points
  /// outside the support of the model's forces and constraints grown by this many rings are
  /// fixed; -1: off
  int local_sculpting_margin = -1;
  bool operator==(const SceneBoundary&) const = default;
};

/// A regular grid with a flat rest shape origin + i h axis_u + j h axis_v.
struct SceneGrid {
  int nodes_u = 0;
  int nodes_v = 0;
  double spacing = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  bool operator==(const SceneGrid&) const = default;
};

/// Fitting a model's initial shape to points instead of giving it ("fit"; io/scene_fit.h): the
/// parser reads the points and fits, so the spec holds the fitted shape as if it were given.
struct SceneFit {
  std::string points;  ///< as written; a relative path resolves against Scene::directory
  /// D-NURBS (a clamped uniform start over the points' principal axes, fit_dnurbs_curve or
  /// fit_dnurbs_surface with the model's material as the smoothness energy):
  int degree = 3;           ///< in each direction
  int spans = 4;            ///< knot spans in each direction
  double smoothness = 0.0;  ///< DNurbsFitSettings::smoothness
  int iterations = 30;      ///< DNurbsFitSettings::max_iterations
  /// Superquadric (fit_superquadric): SuperquadricFitSettings::max_evaluations.
  int max_evaluations = 20000;
  bool operator==(const SceneFit&) const = default;
};

/// Common D-NURBS settings (DNurbsSettings).
struct SceneDNurbsSettings {
  bool free_weights = false;
  int quadrature_points = 0;
  double minimum_weight = 1e-3;
  bool operator==(const SceneDNurbsSettings&) const = default;
};

struct SceneDNurbsCurve {
  NurbsCurve curve;
  std::string shape_file;  ///< non-empty if the curve came from "shape_file" (written back so)
  double mass_density = 1.0;
  double damping_density = 0.0;
  double tension = 0.0;
  double rigidity = 0.0;
  SceneDNurbsSettings settings;
  std::optional<SceneFit> fit;  ///< present if `curve` was fitted ("fit", written back so)
};

struct SceneDNurbsSurface {
  NurbsSurface surface;
  std::string shape_file;
  double mass_density = 1.0;
  double damping_density = 0.0;
  double a10 = 0.0;
  double a01 = 0.0;
  double b20 = 0.0;
  double b11 = 0.0;
  double b02 = 0.0;
  SceneDNurbsSettings settings;
  std::optional<SceneFit> fit;  ///< present if `surface` was fitted ("fit", written back so)
};

struct SceneSuperquadric {
  /// q_s in the order of SuperquadricShapeParameters: a, a1, a2, a3, e1, e2, t1, t2, b1, b2,
  /// b3, tau, sx, sy.
  Eigen::Matrix<double, 14, 1> shape =
      (Eigen::Matrix<double, 14, 1>() << 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0).finished();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector4d orientation = Eigen::Vector4d(1, 0, 0, 0);  ///< quaternion (w, x, y, z)
  std::string parts = "rigid";                                ///< "rigid", "global" or "full"
  double mass_density = 1.0;
  double damping_alpha = 0.0;
  double damping_beta = 0.0;
  double shape_stiffness = 1.0;                    ///< every q_s entry's spring to its rest value
  Eigen::Vector3d local_stiffness{1.0, 1.0, 0.0};  ///< membrane_u, membrane_v, spring
  int mesh_cells_u = 8;
  int mesh_cells_v = 16;
  int quadrature_points = 3;
  double regularization = 1e-3;
  /// Present if shape, centre and orientation were fitted ("fit", written back so).
  std::optional<SceneFit> fit;
  bool operator==(const SceneSuperquadric&) const = default;
};

struct SceneTerzopoulosSurface {
  SceneGrid grid;
  double mass_density = 1.0;
  double damping_density = 0.0;
  Eigen::Matrix2d eta = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d xi = Eigen::Matrix2d::Zero();
  std::string normal = "classic";  ///< "classic" or "christoffel"
  double delta = 0.5;
  bool operator==(const SceneTerzopoulosSurface&) const = default;
};

struct ScenePdeSurface {
  SceneGrid grid;
  double b = 1.0;
  double c = 2.0;
  double d = 1.0;
  double density = 1.0;
  double damping = 0.0;
  double su0 = 0.0;
  double su1 = 0.0;
  double sv0 = 0.0;
  double sv1 = 0.0;
  std::vector<Eigen::Vector3d> region_centres;  ///< deformation regions (centre, radius)
  std::vector<double> region_radii;
  bool operator==(const ScenePdeSurface&) const = default;
};

struct SceneSnake {
  std::vector<Eigen::Vector3d> nodes;
  bool closed = false;
  double mass_density = 1.0;
  double damping_density = 0.0;
  double tension = 0.0;
  double rigidity = 0.0;
  bool operator==(const SceneSnake&) const = default;
};

/// One model of the scene. `type` strings: "dnurbs_curve", "dnurbs_surface", "superquadric",
/// "terzopoulos_surface", "pde_surface", "snake".
struct SceneModel {
  std::string name;
  /// (The first alternative is default-constructible; D-NURBS specs hold shapes that are not.)
  std::variant<SceneSuperquadric, SceneTerzopoulosSurface, ScenePdeSurface, SceneSnake,
               SceneDNurbsCurve, SceneDNurbsSurface>
      spec;
  SceneBoundary boundary;
  /// Mesh segments per direction = round(scale * output resolution) (at least 3).
  Eigen::Vector2d resolution_scale = Eigen::Vector2d::Ones();
};
/// The model's "type" string.
std::string scene_model_type(const SceneModel& model);

/// Applied forces (dynamics/core/forces.h). Every force acts while start <= t < end.
struct ScenePointForce {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  VectorSchedule force;
  bool operator==(const ScenePointForce&) const = default;
};
struct SceneSpringForce {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  double stiffness = 0.0;
  VectorSchedule target;
  bool operator==(const SceneSpringForce&) const = default;
};
struct SceneControlPointForce {
  int model = 0;
  std::vector<int> control_points;
  VectorSchedule force;
  bool operator==(const SceneControlPointForce&) const = default;
};
struct SceneGravity {
  int model = -1;  ///< -1: every model
  Eigen::Vector3d acceleration = Eigen::Vector3d(0, 0, -9.81);
  bool operator==(const SceneGravity&) const = default;
};
struct ScenePressure {
  int model = 0;
  ScalarSchedule pressure;
  bool operator==(const ScenePressure&) const = default;
};
struct SceneForce {
  std::variant<ScenePointForce, SceneSpringForce, SceneControlPointForce, SceneGravity,
               ScenePressure>
      spec;
  double start = 0.0;
  double end = std::numeric_limits<double>::infinity();
  bool operator==(const SceneForce&) const = default;
};

/// Constraints (constraints/*.h) with Baumgarte parameters.
struct ScenePointTargetConstraint {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  VectorSchedule target;
  bool operator==(const ScenePointTargetConstraint&) const = default;
};
struct ScenePointToPointConstraint {
  int model_a = 0;
  Eigen::Vector2d at_a = Eigen::Vector2d::Zero();
  int model_b = 0;
  Eigen::Vector2d at_b = Eigen::Vector2d::Zero();
  bool operator==(const ScenePointToPointConstraint&) const = default;
};
struct SceneHingeConstraint {
  int model_a = 0;
  Eigen::Vector2d axis_a0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_a1 = Eigen::Vector2d::Zero();
  int model_b = 0;
  Eigen::Vector2d axis_b0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_b1 = Eigen::Vector2d::Zero();
  bool operator==(const SceneHingeConstraint&) const = default;
};
struct SceneControlPointConstraint {
  int model = 0;
  int control_point = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  bool operator==(const SceneControlPointConstraint&) const = default;
};
struct SceneSurfaceNormalConstraint {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  bool operator==(const SceneSurfaceNormalConstraint&) const = default;
};
struct SceneCurveOnSurfaceConstraint {
  int curve_model = 0;
  int surface_model = 0;
  int samples = 8;
  bool operator==(const SceneCurveOnSurfaceConstraint&) const = default;
};
struct SceneConstraint {
  std::variant<ScenePointTargetConstraint, ScenePointToPointConstraint, SceneHingeConstraint,
               SceneControlPointConstraint, SceneSurfaceNormalConstraint,
               SceneCurveOnSurfaceConstraint>
      spec;
  double alpha = 20.0;
  double beta = -1.0;  ///< < 0: beta = alpha (critical damping)
  bool operator==(const SceneConstraint&) const = default;
};

struct SceneIntegrator {
  std::string scheme = "newmark";  ///< "central", "implicit-euler", "newmark"
  double dt = 0.01;
  int newton_iterations = 0;
  double newton_tolerance = 1e-12;
  double newmark_beta = 0.25;
  double newmark_gamma = 0.5;
  /// The run stops as diverged when kinetic + potential energy exceeds this.
  double max_energy = 1e12;
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
  int mesh_every = 0;          ///< a mesh every N steps (0: none but the final one)
  std::string format = "obj";  ///< obj, stl, ply, gltf, glb
  int resolution = 24;         ///< mesh segments per direction
  bool final_mesh = true;
  bool preview = false;        ///< PNG of the final mesh (the tool renders it)
  int log_every = 1;           ///< CSV rows every N steps (and the last step)
  int checkpoint_every = 0;    ///< checkpoint.json every N steps (0: only the final state)
  std::string name = "scene";  ///< file stem of the final mesh, preview
  bool shape_files = false;    ///< the final D-NURBS shapes as shape files <model name>.json
  bool operator==(const SceneOutput&) const = default;
};

/// Static design settings ("design", design/energy_minimization.h DesignSettings): `dnurbs design`
/// minimises the models' elastic energy minus the work of the forces at time 0, subject to the
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
  std::filesystem::path directory;  ///< relative "shape_file"s resolve here; not written
  std::string description;
  std::vector<SceneModel> models;
  std::vector<SceneForce> forces;
  std::vector<SceneConstraint> constraints;
  SceneIntegrator integrator;
  int steps = 0;          ///< run length in steps ("run": {"steps": N}) ...
  double duration = 0.0;  ///< ... or in time ("run": {"duration": T}); exactly one is set
  std::vector<SceneProbe> probes;
  SceneOutput output;
  std::optional<SceneDesign> design;  ///< present if the scene has a "design" section
  /// The number of steps to run: steps, or ceil(duration / dt - 1e-9).
  int step_count() const;
};

/// Model specs compare by value (shapes through their JSON), so scenes compare too.
bool operator==(const SceneDNurbsCurve& a, const SceneDNurbsCurve& b);
bool operator==(const SceneDNurbsSurface& a, const SceneDNurbsSurface& b);
bool operator==(const SceneModel& a, const SceneModel& b);
bool operator==(const Scene& a, const Scene& b);

/// Parses scene JSON. `source` names the text in messages; relative shape files resolve against
/// `directory`. Throws Error "<source>: <json path>: <what was expected>" for every malformed
/// key (unparseable JSON with line and column, missing, unknown or mistyped keys, values out of
/// range, unknown model names or indices, bad shapes).
Scene parse_scene_json(const std::string& text, const std::string& source = "<string>",
                       const std::filesystem::path& directory = {});
/// Reads a scene file (Error naming the file if it cannot be read).
Scene read_scene_file(const std::filesystem::path& path);
/// The scene as JSON text (every key; numbers round-trip exactly).
std::string scene_to_json(const Scene& scene);
/// A hash (16 hex digits, FNV-1a 64) of everything that determines the simulated state (the
/// scene without "output" and "description"): checkpoints carry it.
std::string scene_state_hash(const Scene& scene);

}  // namespace dnurbs
