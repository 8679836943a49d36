#pragma once
// Scene type "deformation_field" (docs/scene-format.md): a DeformationFieldModel
// (dynamics/fields/deformation_field_model.h), the cascade of deformation fields of Goldenstein et
// al. 2005 (eqs. 1-4) given either as the deformable face of a geometry image
// (surface/deformable_face.h, key "face") or as a list of stages with analytic or geometry image
// fields (key "stages"). Each parameter is dynamic (a coordinate with its stiffness) or keyed (a
// schedule the scene prescribes, io/scene_prescribed.h); the model's meshes are adaptive to the
// key "max_error" (Goldenstein et al. 2005, section 5.2.3).

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/fields/deformation_field_model.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"
#include "dnurbs/surface/deformable_face.h"

namespace dnurbs {

/// A vector field V(u, v) of a stage (Goldenstein et al. 2005, section 3.2).
struct SceneVectorField {
  std::string type = "uniform";  ///< uniform, plane, gaussian or geometry_image
  /// uniform: V; gaussian: V at the centre; plane: the origin.
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_axis = Eigen::Vector3d::UnitX();  ///< plane: V = origin + u u_axis + v v_axis
  Eigen::Vector3d v_axis = Eigen::Vector3d::UnitY();
  /// gaussian: V = vector exp(-|(u, v) - centre|^2 / radius^2).
  Eigen::Vector2d centre = Eigen::Vector2d::Constant(0.5);
  double radius = 0.25;
  std::string file;  ///< geometry_image: the file as written (surface/deformable_face.h format)
  std::shared_ptr<const SampledVectorField> image;  ///< its samples, read with the scene
  /// V as a function of (u, v).
  VectorField function() const;
};

/// One stage: p = V (constant, eqs. 2-3) or p += s V (add_vector, eq. 4) with s the named
/// parameter, or 1 when `parameter` is empty.
struct SceneFieldStage {
  bool constant = false;
  SceneVectorField field;
  std::string parameter;
};

/// A parameter q_k: dynamic (a coordinate with stiffness k_k toward 0 and an initial value) or
/// keyed (its value prescribed by `schedule`).
struct SceneFieldParameter {
  std::string name;
  double stiffness = 0.0;
  double initial = 0.0;
  bool keyed = false;
  ScalarSchedule schedule;
  int coordinate = 0;  ///< its index in q (derived from the keys, not written)
};

struct SceneDeformationField final : SceneModelSpec {
  std::string face;  ///< the geometry image file of the face preset, or empty
  std::shared_ptr<const DeformableFace> face_model;
  std::vector<SceneFieldStage> stages;  ///< without a face
  ParameterDomain domain;               ///< without a face (the face's is the unit square)
  std::vector<SceneFieldParameter> parameters;
  /// Material, quadrature and tessellation; the stiffness comes from `parameters` at build().
  DeformationFieldSettings settings;

  std::unique_ptr<SceneModelSpec> clone() const override;
  std::string type() const override { return "deformation_field"; }
  void write(JsonOut& model) const override;
  /// The model with every keyed parameter (and every face parameter the scene does not list)
  /// fixed at its value at t = 0.
  std::unique_ptr<Model> build() const override;
  /// The keyed parameters at `time`.
  std::vector<std::pair<int, double>> prescribed_coordinates(double time) const override;
};

/// Reads the keys of a "deformation_field" model.
std::unique_ptr<SceneModelSpec> read_deformation_field_scene(const SceneReader& reader,
                                                             const JsonValue& model,
                                                             const std::string& path);

}  // namespace dnurbs
