#include "dnurbs/io/models/terzopoulos_surface_scene.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {

std::pair<double, std::string> SceneTerzopoulosSurface::memory_estimate() const {
  const double nodes = static_cast<double>(grid.nodes_u) * static_cast<double>(grid.nodes_v);
  const double fill = std::max(1.0, std::log(nodes) / std::log(9e4));
  return {8e3 * nodes * fill, "grid.nodes"};
}

std::unique_ptr<SceneModelSpec> SceneTerzopoulosSurface::clone() const {
  return std::make_unique<SceneTerzopoulosSurface>(*this);
}

void SceneTerzopoulosSurface::write(JsonOut& model) const {
  model["grid"] = scene_grid_json(grid);
  model["normal"] = to_string(settings.normal);
  model["delta"] = settings.delta;
  model["material"] = {{"mass_density", material.mass_density},
                       {"damping_density", material.damping_density},
                       {"eta", matrix2_json(material.eta)},
                       {"xi", matrix2_json(material.xi)}};
  if (plastic) {
    model["plastic"] = plastic_flow_json(*plastic);
  }
}

std::unique_ptr<Model> SceneTerzopoulosSurface::build() const {
  auto surface =
      std::make_unique<TerzopoulosSurface>(grid.grid(), grid.rest_positions(), material, settings);
  surface->set_plastic_flow(plastic);
  return surface;
}

std::unique_ptr<SceneModelSpec> read_terzopoulos_surface_scene(const SceneReader& reader,
                                                               const JsonValue& model,
                                                               const std::string& path) {
  check_model_keys(reader, model, path, "terzopoulos_surface",
                   {"grid", "normal", "delta", "plastic"});
  auto spec = std::make_unique<SceneTerzopoulosSurface>();
  spec->grid = read_scene_grid(reader, model, path);
  spec->plastic = read_plastic_flow(reader, model, path);
  if (const JsonValue* normal = reader.find(model, "normal")) {
    const std::string name = reader.choice(*normal, join_json_path(path, "normal"),
                                           {"classic", "christoffel", "christoffel_unnormalized"});
    spec->settings.normal = parse_normal_approximation(name);
  }
  reader.number_key(model, path, "delta", spec->settings.delta, 0.0, true);
  const JsonValue material =
      model_material(reader, model, path, {"mass_density", "damping_density", "eta", "xi"});
  const std::string material_path = join_json_path(path, "material");
  reader.number_key(material, material_path, "mass_density", spec->material.mass_density, 0.0,
                    true);
  reader.number_key(material, material_path, "damping_density", spec->material.damping_density, 0.0,
                    false);
  if (const JsonValue* eta = reader.find(material, "eta")) {
    spec->material.eta = reader.matrix2(*eta, join_json_path(material_path, "eta"));
  }
  if (const JsonValue* xi = reader.find(material, "xi")) {
    spec->material.xi = reader.matrix2(*xi, join_json_path(material_path, "xi"));
  }
  return spec;
}

}  // namespace dnurbs
