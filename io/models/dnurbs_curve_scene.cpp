#include "io/models/dnurbs_curve_scene.h"

#include "io/models/dnurbs_scene_keys.h"
#include "io/scene_fit.h"
#include "io/scene_model_keys.h"

namespace dnurbs {

std::unique_ptr<SceneModelSpec> SceneDNurbsCurve::clone() const {
  return std::make_unique<SceneDNurbsCurve>(*this);
}

void SceneDNurbsCurve::write(JsonOut& model) const {
  write_scene_shape(curve ? std::optional<Shape>(*curve) : std::nullopt, shape_file, fit, model);
  const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  model["material"] = {{"mass_density", material.mass_density(origin)},
                       {"damping_density", material.damping_density(origin)},
                       {"tension", material.tension(origin)},
                       {"rigidity", material.rigidity(origin)}};
  write_dnurbs_settings(settings, model);
}

std::unique_ptr<Model> SceneDNurbsCurve::build() const {
  if (!curve) {
    throw make_error("the curve's \"fit\" has not been run (fit_initial_shapes)");
  }
  return std::make_unique<DNurbsCurve>(*curve, material, settings);
}

const SceneFit* SceneDNurbsCurve::pending_fit() const {
  return fit && !curve ? &*fit : nullptr;
}

void SceneDNurbsCurve::run_fit(const Eigen::MatrixX3d& points) {
  curve = fit_scene_curve(points, fit.value(), material, settings);
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
SceneDNurbsCurve::naive_variant() const {
  if (settings.weight_mode == WeightMode::kFree) {
    return std::nullopt;
  }
  auto naive = std::make_unique<SceneDNurbsCurve>(*this);
  naive->settings.weight_mode = WeightMode::kFree;
  return std::pair{std::unique_ptr<SceneModelSpec>(std::move(naive)),
                   std::string("fixed weights (naive: free weights)")};
}

std::unique_ptr<SceneModelSpec> read_dnurbs_curve_scene(const SceneReader& reader,
                                                        const JsonValue& model,
                                                        const std::string& path) {
  check_model_keys(reader, model, path, "dnurbs_curve",
                   {"shape", "shape_file", "fit", "weights", "quadrature_points", "minimum_weight"});
  auto spec = std::make_unique<SceneDNurbsCurve>();
  const JsonValue material =
      model_material(reader, model, path, {"mass_density", "damping_density", "tension", "rigidity"});
  const std::string material_path = join_json_path(path, "material");
  double mass_density = 1.0;
  double damping_density = 0.0;
  double tension = 0.0;
  double rigidity = 0.0;
  reader.number_key(material, material_path, "mass_density", mass_density, 0.0, false);
  reader.number_key(material, material_path, "damping_density", damping_density, 0.0, false);
  reader.number_key(material, material_path, "tension", tension, 0.0, false);
  reader.number_key(material, material_path, "rigidity", rigidity, 0.0, false);
  spec->material.mass_density = mass_density;
  spec->material.damping_density = damping_density;
  spec->material.tension = tension;
  spec->material.rigidity = rigidity;
  read_dnurbs_settings(reader, model, path, spec->settings);
  spec->fit = read_fit(reader, model, path, true, {"shape", "shape_file"});
  if (!spec->fit) {
    spec->curve =
        read_scene_shape<NurbsCurve>(reader, model, path, spec->shape_file, "nurbs_curve");
  }
  return spec;
}

}  // namespace dnurbs
