#pragma once
// The constraint types of scene files (docs/scene-format.md, "constraints"). A type is a struct
// of its keys; SceneConstraintOf<Keys> makes it a SceneConstraintSpec whose reader, writer and
// library constraints (constraints/*.h) are defined in io/scene_constraints.cpp for the types
// below. Every constraint has Baumgarte parameters alpha and beta (read by the scene dispatcher).

#include <memory>
#include <string>

#include <Eigen/Core>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// A scene constraint of the type whose keys are `Keys` (a struct with the keys as members and
/// `static constexpr const char* kType`, the "type" string).
template <typename Keys>
class SceneConstraintOf final : public SceneConstraintSpec, public Keys {
 public:
  std::unique_ptr<SceneConstraintSpec> clone() const override {
    return std::make_unique<SceneConstraintOf>(*this);
  }
  std::string type() const override { return Keys::kType; }
  void write(JsonOut& json) const override;
  void add(ConstraintSolver& solver, System& system,
           const BaumgarteParameters& parameters) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
  /// Reads the type's keys (the reader of io/scene_registry.cpp's constraint table).
  static std::unique_ptr<SceneConstraintSpec> read(const SceneReader& reader,
                                                   const ModelNames& names,
                                                   const JsonValue& constraint,
                                                   const std::string& path);
};

/// "point_target": a material point held on a target schedule.
struct PointTargetKeys {
  static constexpr const char* kType = "point_target";
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  VectorSchedule target;
};

/// "point_to_point": a ball joint between material points of two models.
struct PointToPointKeys {
  static constexpr const char* kType = "point_to_point";
  int model_a = 0;
  Eigen::Vector2d at_a = Eigen::Vector2d::Zero();
  int model_b = 0;
  Eigen::Vector2d at_b = Eigen::Vector2d::Zero();
};

/// "hinge": two pairs of material points joined (an axis shared by two models).
struct HingeKeys {
  static constexpr const char* kType = "hinge";
  int model_a = 0;
  Eigen::Vector2d axis_a0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_a1 = Eigen::Vector2d::Zero();
  int model_b = 0;
  Eigen::Vector2d axis_b0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_b1 = Eigen::Vector2d::Zero();
};

/// "control_point": a control point moved to a target by Baumgarte dynamics.
struct ControlPointKeys {
  static constexpr const char* kType = "control_point";
  int model = 0;
  int control_point = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

/// "surface_normal": a surface normal held parallel to a direction.
struct SurfaceNormalKeys {
  static constexpr const char* kType = "surface_normal";
  int model = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

/// "curve_on_surface": a curve held on a surface at samples, glued to surface points frozen at
/// creation (follow = false: curve_on_surface_constraints) or following their nearest surface
/// points (follow = true: CurveOnSurfaceConstraint, the curve may slide over the surface).
struct CurveOnSurfaceKeys {
  static constexpr const char* kType = "curve_on_surface";
  int curve_model = 0;
  int surface_model = 0;
  int samples = 8;
  bool follow = false;
};

using ScenePointTargetConstraint = SceneConstraintOf<PointTargetKeys>;
using ScenePointToPointConstraint = SceneConstraintOf<PointToPointKeys>;
using SceneHingeConstraint = SceneConstraintOf<HingeKeys>;
using SceneControlPointConstraint = SceneConstraintOf<ControlPointKeys>;
using SceneSurfaceNormalConstraint = SceneConstraintOf<SurfaceNormalKeys>;
using SceneCurveOnSurfaceConstraint = SceneConstraintOf<CurveOnSurfaceKeys>;
extern template class SceneConstraintOf<PointTargetKeys>;
extern template class SceneConstraintOf<PointToPointKeys>;
extern template class SceneConstraintOf<HingeKeys>;
extern template class SceneConstraintOf<ControlPointKeys>;
extern template class SceneConstraintOf<SurfaceNormalKeys>;
extern template class SceneConstraintOf<CurveOnSurfaceKeys>;

}  // namespace dnurbs
