#pragma once
// Scene type "superquadric" (docs/scene-format.md): a deformable superquadric
// (dynamics/superquadric/deformable_superquadric_model.h) with its shape parameters, pose, parts
// and material, or fitted to points.

#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

struct SceneSuperquadric final : SceneModelSpec {
  SceneSuperquadric();
  /// q_s in the order of SuperquadricShapeParameters: a, a1, a2, a3, e1, e2, t1, t2, b1, b2, b3,
  /// tau, sx, sy.
  SuperquadricShapeParameters shape;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector4d orientation = Eigen::Vector4d(1, 0, 0, 0);  ///< quaternion (w, x, y, z)
  /// Parts (rigid(), global() or full(): "parts"), material, mesh and quadrature. Scene default
  /// of local_stiffness: (1, 1, 0).
  DeformableSuperquadricSettings settings;
  /// Present if shape, centre and orientation are (to be) fitted ("fit", written back so).
  std::optional<SceneFit> fit;
  bool fitted = false;  ///< the fit has run

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "superquadric"; }
  void write(JsonOut& model) const override;
  std::unique_ptr<Model> build() const override;
  const SceneFit* pending_fit() const override;
  /// fit_superquadric (design/superquadric_fitting.h) with the fit's max_evaluations.
  void run_fit(const Eigen::MatrixX3d& points) override;
  /// Rigid or global parts: every part (rigid, global and local).
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override;
};

/// Reads the keys of a "superquadric" model.
std::unique_ptr<SceneModelSpec> read_superquadric_scene(const SceneReader& reader,
                                                        const JsonValue& model,
                                                        const std::string& path);

}  // namespace dnurbs
