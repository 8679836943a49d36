#pragma once
// Scene type "swung_surface" (docs/scene-format.md): a swung D-NURBS surface
// (dynamics/swung/dnurbs_swung_surface.h; Qin & Terzopoulos, Dynamic NURBS swung surfaces for
// physics-based shape design, CAD 27(2) 1995) from its profile and trajectory curves (inline or
// shape files) or from a named prototype (nurbs/swung_shapes.h), optionally refined, with its
// material, settings (among them the rest shape keys "rest_shape" and "plastic" of the other
// D-NURBS types, io/scene_model_keys.h) and curve fixes.

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// A named prototype (scene key "prototype") and its dimensions; only the keys of its kind are
/// read and written.
struct SceneSwungPrototype {
  /// "sphere" (radius), "torus" (major_radius, minor_radius), "cylinder" and "cone" (radius,
  /// height, profile_control_points), "hat" (brim_radius, crown_radius, height) or
  /// "open_profile" (start, end, profile_control_points).
  std::string kind = "sphere";
  double radius = 1.0;
  double major_radius = 2.0;
  double minor_radius = 0.5;
  double height = 1.0;
  double brim_radius = 1.5;
  double crown_radius = 0.8;
  int profile_control_points = 4;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  ///< open_profile: [x, z] of u = 0
  Eigen::Vector2d end = Eigen::Vector2d(1.0, 0.0);  ///< open_profile: [x, z] of u = 1

  /// The prototype's swung surface (nurbs/swung_shapes.h); throws Error from the generator.
  SwungSurface surface() const;
};

struct SceneSwungSurface final : SceneModelSpec {
  std::optional<SceneSwungPrototype> prototype;  ///< set if the surface came from "prototype"
  /// The surface before refinement: the prototype's, or the curves' (with alpha).
  SwungSurface surface = SceneSwungPrototype{}.surface();
  std::string profile_file;     ///< non-empty if the profile came from a shape file
  std::string trajectory_file;  ///< likewise the trajectory
  /// Knots inserted inside every non-empty span of the profile and of the trajectory
  /// (refine_swung_surface).
  Eigen::Vector2i refine = Eigen::Vector2i::Zero();
  bool fix_profile = false;        ///< DNurbsSwungSurface::fix_profile
  bool fix_trajectory = false;     ///< DNurbsSwungSurface::fix_trajectory
  bool fix_poles = true;           ///< DNurbsSwungSurface::fix_poles
  DNurbsSurfaceMaterial material;  ///< constants (scene files give numbers)
  DNurbsSwungSettings settings;

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "swung_surface"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  /// The tensor-product D-NURBS surface of the same (refined) shape, material and weight mode
  /// (a "dnurbs_surface" spec read through the scene registry): 3 m n coordinates against the
  /// swung 2 (m + n) (fixed weights).
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;

  /// The refined surface the model is built from.
  SwungSurface refined_surface() const;
};

/// Reads the keys of a "swung_surface" model.
std::unique_ptr<SceneModelSpec> read_swung_surface_scene(const SceneReader& reader,
                                                         const JsonValue& model,
                                                         const std::string& path);

}  // namespace dnurbs
