#pragma once
// Scene types "dnurbs_curve" and "dnurbs_surface" (docs/scene-format.md): a D-NURBS curve or
// tensor-product surface (dynamics/dnurbs/) with its shape, material and settings. What they
// share is SceneDNurbsModel: the initial shape ("shape", "shape_file" or "fit"), the material
// as a table of named constants, the D-NURBS settings, and the naive variant of the cost report
// (free weights). Each type derives from it and names its shape member, keys and model class.
// Their readers, read_dnurbs_curve_scene and read_dnurbs_surface_scene, are declared by
// io/scene_registry.cpp from io/scene_model_types.def.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/io/models/dnurbs_scene_keys.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// A stiffness constant of a scene file: its key and the field of the material it sets
/// (default 0, like "damping_density"; "mass_density" defaults to 1).
template <typename Material>
struct SceneMaterialKey {
  const char* key;
  MaterialFunction Material::*field;
};

/// The scene spec of a D-NURBS model type. `Spec` (CRTP) provides:
///   kType            the "type" string ("dnurbs_curve")
///   kShapeType       the shape-file type of its shape ("nurbs_curve")
///   kShape           pointer to its member std::optional<Shape> (absent while a fit is pending)
///   kStiffnessKeys   std::array of SceneMaterialKey<Material>, the material keys after
///                    "mass_density" and "damping_density", in the order they are written
///   run_fit          the fit of its shape to points
template <typename Spec, typename Shape, typename Material, typename ModelType>
struct SceneDNurbsModel : SceneModelSpec {
  std::string shape_file;  ///< non-empty if the shape came from "shape_file" (written back so)
  Material material;       ///< constants (scene files give numbers)
  DNurbsSettings settings;
  std::optional<SceneFit> fit;  ///< present if the shape is (to be) fitted ("fit", written back)

  std::unique_ptr<SceneModelSpec> clone() const override { return std::make_unique<Spec>(self()); }
  std::string type() const override { return Spec::kType; }

  void write(JsonOut& model) const override {
    const std::optional<Shape>& shape = self().*Spec::kShape;
    write_scene_shape(shape ? std::optional<dnurbs::Shape>(*shape) : std::nullopt, shape_file, fit,
                      model);
    const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    JsonOut constants = {{"mass_density", material.mass_density(origin)},
                         {"damping_density", material.damping_density(origin)}};
    for (const auto& key : Spec::kStiffnessKeys) {
      constants[key.key] = (material.*key.field)(origin);
    }
    model["material"] = constants;
    write_dnurbs_settings(settings, model);
  }

  std::unique_ptr<Model> build() const override {
    const std::optional<Shape>& shape = self().*Spec::kShape;
    if (!shape) {
      throw make_error("the ", Spec::kType,
                       " model's \"fit\" has not been run (fit_initial_shapes)");
    }
    return std::make_unique<ModelType>(*shape, material, settings);
  }

  const SceneFit* pending_fit() const override {
    return fit && !(self().*Spec::kShape) ? &*fit : nullptr;
  }

  /// Fixed weights: free weights.
  std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>> naive_variant()
      const override {
    if (settings.weight_mode == WeightMode::kFree) {
      return std::nullopt;
    }
    auto naive = std::make_unique<Spec>(self());
    naive->settings.weight_mode = WeightMode::kFree;
    return std::pair{std::unique_ptr<SceneModelSpec>(std::move(naive)),
                     std::string("fixed weights (naive: free weights)")};
  }

  /// Reads the keys of a model of type Spec::kType.
  static std::unique_ptr<SceneModelSpec> read(const SceneReader& reader, const JsonValue& model,
                                              const std::string& path) {
    check_model_keys(
        reader, model, path, Spec::kType,
        {"shape", "shape_file", "make", "fit", "weights", "quadrature_points", "minimum_weight",
         "weight_inertia", "weight_stiffness", "rest_shape", "plastic"});
    auto spec = std::make_unique<Spec>();
    std::vector<const char*> keys = {"mass_density", "damping_density"};
    for (const auto& key : Spec::kStiffnessKeys) {
      keys.push_back(key.key);
    }
    const JsonValue material = model_material(reader, model, path, keys);
    const std::string material_path = join_json_path(path, "material");
    double mass_density = 1.0;
    double damping_density = 0.0;
    reader.number_key(material, material_path, "mass_density", mass_density, 0.0, false);
    reader.number_key(material, material_path, "damping_density", damping_density, 0.0, false);
    spec->material.mass_density = mass_density;
    spec->material.damping_density = damping_density;
    for (const auto& key : Spec::kStiffnessKeys) {
      double value = 0.0;
      reader.number_key(material, material_path, key.key, value, 0.0, false);
      spec->material.*key.field = value;
    }
    read_dnurbs_settings(reader, model, path, spec->settings);
    spec->fit = read_fit(reader, model, path, true, {"shape", "shape_file", "make"});
    if (!spec->fit) {
      (*spec).*Spec::kShape =
          read_scene_shape<Shape>(reader, model, path, spec->shape_file, Spec::kShapeType);
    }
    return spec;
  }

 private:
  const Spec& self() const { return static_cast<const Spec&>(*this); }
};

/// "dnurbs_curve": stiffness keys per unit length, tension weighing |x_u|^2 and rigidity
/// |x_uu|^2 (Terzopoulos 2003, eq. 1.26).
struct SceneDNurbsCurve final
    : SceneDNurbsModel<SceneDNurbsCurve, NurbsCurve, DNurbsCurveMaterial, DNurbsCurve> {
  static constexpr const char* kType = "dnurbs_curve";
  static constexpr const char* kShapeType = "nurbs_curve";
  static constexpr std::array<SceneMaterialKey<DNurbsCurveMaterial>, 2> kStiffnessKeys = {{
      {"tension", &DNurbsCurveMaterial::tension},
      {"rigidity", &DNurbsCurveMaterial::rigidity},
  }};
  std::optional<NurbsCurve> curve;  ///< absent while a fit is pending
  static constexpr auto kShape = &SceneDNurbsCurve::curve;
  void run_fit(const Eigen::MatrixX3d& points) override;  ///< fit_scene_curve (io/scene_fit.h)
};

/// "dnurbs_surface": stiffness keys per unit parametric area, the thin-plate-under-tension
/// weights a10 |x_u|^2 + a01 |x_v|^2 + b20 |x_uu|^2 + b11 |x_uv|^2 + b02 |x_vv|^2 (Terzopoulos
/// 2003, eq. 1.27).
struct SceneDNurbsSurface final
    : SceneDNurbsModel<SceneDNurbsSurface, NurbsSurface, DNurbsSurfaceMaterial, DNurbsSurface> {
  static constexpr const char* kType = "dnurbs_surface";
  static constexpr const char* kShapeType = "nurbs_surface";
  static constexpr std::array<SceneMaterialKey<DNurbsSurfaceMaterial>, 5> kStiffnessKeys = {{
      {"a10", &DNurbsSurfaceMaterial::a10},
      {"a01", &DNurbsSurfaceMaterial::a01},
      {"b20", &DNurbsSurfaceMaterial::b20},
      {"b11", &DNurbsSurfaceMaterial::b11},
      {"b02", &DNurbsSurfaceMaterial::b02},
  }};
  std::optional<NurbsSurface> surface;  ///< absent while a fit is pending
  static constexpr auto kShape = &SceneDNurbsSurface::surface;
  void run_fit(const Eigen::MatrixX3d& points) override;  ///< fit_scene_surface (io/scene_fit.h)
};

}  // namespace dnurbs
