#pragma once
// The constraint types of scene files (docs/scene-format.md, "constraints"), each with its keys,
// reader, writer and the library constraints it adds (constraints/*.h). Every constraint has
// Baumgarte parameters alpha and beta (read by the scene dispatcher).

#include <memory>
#include <string>

#include <Eigen/Core>

#include "io/scene_reader.h"
#include "io/scene_spec.h"

namespace dnurbs {

/// "point_target": a material point held on a target schedule.
struct ScenePointTargetConstraint final : SceneConstraintSpec {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  VectorSchedule target;
  std::unique_ptr<SceneConstraintSpec> clone() const override;
  std::string type() const override { return "point_target"; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "point_to_point": a ball joint between material points of two models.
struct ScenePointToPointConstraint final : SceneConstraintSpec {
  int model_a = 0;
  Eigen::Vector2d at_a = Eigen::Vector2d::Zero();
  int model_b = 0;
  Eigen::Vector2d at_b = Eigen::Vector2d::Zero();
  std::unique_ptr<SceneConstraintSpec> clone() const override;
  std::string type() const override { return "point_to_point"; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "hinge": two pairs of material points joined (an axis shared by two models).
struct SceneHingeConstraint final : SceneConstraintSpec {
  int model_a = 0;
  Eigen::Vector2d axis_a0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_a1 = Eigen::Vector2d::Zero();
  int model_b = 0;
  Eigen::Vector2d axis_b0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_b1 = Eigen::Vector2d::Zero();
  std::unique_ptr<SceneConstraintSpec> clone() const override;
  std::string type() const override { return "hinge"; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "control_point": a control point moved to a target by Baumgarte dynamics.
struct SceneControlPointConstraint final : SceneConstraintSpec {
  int model = 0;
  int control_point = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  std::unique_ptr<SceneConstraintSpec> clone() const override;
  std::string type() const override { return "control_point"; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "surface_normal": a surface normal held parallel to a direction.
struct SceneSurfaceNormalConstraint final : SceneConstraintSpec {
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  std::unique_ptr<SceneConstraintSpec> clone() const override;
  std::string type() const override { return "surface_normal"; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// "curve_on_surface": a curve glued onto a surface at samples.
struct SceneCurveOnSurfaceConstraint final : SceneConstraintSpec {
  int curve_model = 0;
  int surface_model = 0;
  int samples = 8;
  std::unique_ptr<SceneConstraintSpec> clone() const override;
  std::string type() const override { return "curve_on_surface"; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// The readers of io/scene_registry.cpp's constraint table.
std::unique_ptr<SceneConstraintSpec> read_point_target_constraint(const SceneReader& reader,
                                                                  const ModelNames& names,
                                                                  const JsonValue& constraint,
                                                                  const std::string& path);
std::unique_ptr<SceneConstraintSpec> read_point_to_point_constraint(const SceneReader& reader,
                                                                    const ModelNames& names,
                                                                    const JsonValue& constraint,
                                                                    const std::string& path);
std::unique_ptr<SceneConstraintSpec> read_hinge_constraint(const SceneReader& reader,
                                                           const ModelNames& names,
                                                           const JsonValue& constraint,
                                                           const std::string& path);
std::unique_ptr<SceneConstraintSpec> read_control_point_constraint(const SceneReader& reader,
                                                                   const ModelNames& names,
                                                                   const JsonValue& constraint,
                                                                   const std::string& path);
std::unique_ptr<SceneConstraintSpec> read_surface_normal_constraint(const SceneReader& reader,
                                                                    const ModelNames& names,
                                                                    const JsonValue& constraint,
                                                                    const std::string& path);
std::unique_ptr<SceneConstraintSpec> read_curve_on_surface_constraint(const SceneReader& reader,
                                                                      const ModelNames& names,
                                                                      const JsonValue& constraint,
                                                                      const std::string& path);

}  // namespace dnurbs
