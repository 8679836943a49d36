#pragma once
// The applied-force types of scene files (docs/scene-format.md, "forces"), each with its keys,
// reader, writer and the library force it adds (dynamics/core/forces.h). Every force acts while
// start <= t < end (keys "start" and "end", read by the scene dispatcher).

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// "point": a force schedule at a material point.
struct ScenePointForce final : SceneForceSpec {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  VectorSchedule force;
  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "point"; }
  void write(JsonOut& json) const override;
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "spring": a mouse spring of stiffness k from a material point to a target schedule.
struct SceneSpringForce final : SceneForceSpec {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  double stiffness = 0.0;
  VectorSchedule target;
  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "spring"; }
  void write(JsonOut& json) const override;
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "control_point": a force schedule on control points (or nodes) directly.
struct SceneControlPointForce final : SceneForceSpec {
  int model = 0;
  std::vector<int> control_points;
  VectorSchedule force;
  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "control_point"; }
  void write(JsonOut& json) const override;
  /// Throws SceneKeyError(".control_points[k]") for an index the model does not have.
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "gravity": the acceleration g on one model or (model -1) on every model.
struct SceneGravity final : SceneForceSpec {
  int model = -1;  ///< -1: every model
  Eigen::Vector3d acceleration = Eigen::Vector3d(0, 0, -9.81);
  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "gravity"; }
  void write(JsonOut& json) const override;
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "pressure": a pressure schedule along the surface normal.
struct ScenePressure final : SceneForceSpec {
  int model = 0;
  ScalarSchedule pressure;
  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "pressure"; }
  void write(JsonOut& json) const override;
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "wind": the viscous fluid force drag (n . (v(t) - xdot)) n per unit area (dynamics/core/forces.h
/// wind, Terzopoulos et al. 1987) on one surface model or (model -1) on every surface model.
struct SceneWind final : SceneForceSpec {
  int model = -1;  ///< -1: every surface model (curves feel no wind)
  VectorSchedule velocity;
  double drag = 0.0;
  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "wind"; }
  void write(JsonOut& json) const override;
  /// Throws SceneKeyError(".model") when the model named is a curve.
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// The readers of io/scene_registry.cpp's force table.
std::unique_ptr<SceneForceSpec> read_point_force(const SceneReader& reader, const ModelNames& names,
                                                 const JsonValue& force, const std::string& path);
std::unique_ptr<SceneForceSpec> read_spring_force(const SceneReader& reader,
                                                  const ModelNames& names, const JsonValue& force,
                                                  const std::string& path);
std::unique_ptr<SceneForceSpec> read_control_point_force(const SceneReader& reader,
                                                         const ModelNames& names,
                                                         const JsonValue& force,
                                                         const std::string& path);
std::unique_ptr<SceneForceSpec> read_gravity(const SceneReader& reader, const ModelNames& names,
                                             const JsonValue& force, const std::string& path);
std::unique_ptr<SceneForceSpec> read_pressure(const SceneReader& reader, const ModelNames& names,
                                              const JsonValue& force, const std::string& path);
std::unique_ptr<SceneForceSpec> read_wind(const SceneReader& reader, const ModelNames& names,
                                          const JsonValue& force, const std::string& path);

}  // namespace dnurbs
