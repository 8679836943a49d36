#include "io/models/dnurbs_surface_scene.h"

#include "io/models/dnurbs_scene_keys.h"
#include "io/scene_fit.h"
#include "io/scene_model_keys.h"

namespace dnurbs {

std::unique_ptr<SceneModelSpec> SceneDNurbsSurface::clone() const {
  return std::make_unique<SceneDNurbsSurface>(*this);
}

void SceneDNurbsSurface::write(JsonOut& model) const {
  write_scene_shape(surface ? std::optional<Shape>(*surface) : std::nullopt, shape_file, fit,
                    model);
  const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  model["material"] = {{"mass_density", material.mass_density(origin)},
                       {"damping_density", material.damping_density(origin)},
                       {"a10", material.a10(origin)},
                       {"a01", material.a01(origin)},
                       {"b20", material.b20(origin)},
                       {"b11", material.b11(origin)},
                       {"b02", material.b02(origin)}};
  write_dnurbs_settings(settings, model);
}

std::unique_ptr<Model> SceneDNurbsSurface::build() const {
  if (!surface) {
    throw make_error("the surface's \"fit\" has not been run (fit_initial_shapes)");
  }
  return std::make_unique<DNurbsSurface>(*surface, material, settings);
}

const SceneFit* SceneDNurbsSurface::pending_fit() const {
  return fit && !surface ? &*fit : nullptr;
}

void SceneDNurbsSurface::run_fit(const Eigen::MatrixX3d& points) {
  surface = fit_scene_surface(points, fit.value(), material, settings);
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
SceneDNurbsSurface::naive_variant() const {
  if (settings.weight_mode == WeightMode::kFree) {
    return std::nullopt;
  }
  auto naive = std::make_unique<SceneDNurbsSurface>(*this);
  naive->settings.weight_mode = WeightMode::kFree;
  return std::pair{std::unique_ptr<SceneModelSpec>(std::move(naive)),
                   std::string("fixed weights (naive: free weights)")};
}

std::unique_ptr<SceneModelSpec> read_dnurbs_surface_scene(const SceneReader& reader,
                                                          const JsonValue& model,
                                                          const std::string& path) {
  check_model_keys(reader, model, path, "dnurbs_surface",
                   {"shape", "shape_file", "fit", "weights", "quadrature_points", "minimum_weight"});
  auto spec = std::make_unique<SceneDNurbsSurface>();
  const JsonValue material =
      model_material(reader, model, path,
                     {"mass_density", "damping_density", "a10", "a01", "b20", "b11", "b02"});
  const std::string material_path = join_json_path(path, "material");
  double values[7] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const char* keys[7] = {"mass_density", "damping_density", "a10", "a01", "b20", "b11", "b02"};
  for (int k = 0; k < 7; ++k) {
    reader.number_key(material, material_path, keys[k], values[k], 0.0, false);
  }
  MaterialFunction* targets[7] = {&spec->material.mass_density, &spec->material.damping_density,
                                  &spec->material.a10,          &spec->material.a01,
                                  &spec->material.b20,          &spec->material.b11,
                                  &spec->material.b02};
  for (int k = 0; k < 7; ++k) {
    *targets[k] = values[k];
  }
  read_dnurbs_settings(reader, model, path, spec->settings);
  spec->fit = read_fit(reader, model, path, true, {"shape", "shape_file"});
  if (!spec->fit) {
    spec->surface =
        read_scene_shape<NurbsSurface>(reader, model, path, spec->shape_file, "nurbs_surface");
  }
  return spec;
}

}  // namespace dnurbs
