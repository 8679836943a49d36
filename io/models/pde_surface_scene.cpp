#include "dnurbs/io/models/pde_surface_scene.h"

#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {

std::unique_ptr<SceneModelSpec> ScenePdeSurface::clone() const {
  return std::make_unique<ScenePdeSurface>(*this);
}

void ScenePdeSurface::write(JsonOut& model) const {
  model["grid"] = scene_grid_json(grid);
  model["material"] = {{"b", material.b},
                       {"c", material.c},
                       {"d", material.d},
                       {"density", material.mass_density},
                       {"damping", material.damping_density},
                       {"su0", material.tangent_u0},
                       {"su1", material.tangent_u1},
                       {"sv0", material.tangent_v0},
                       {"sv1", material.tangent_v1}};
  JsonOut list = JsonOut::array();
  for (const DeformationRegion& region : regions) {
    list.push_back(
        {{"centre", json_array<3>(region.centre)}, {"radius", region.deformation_radius}});
  }
  model["regions"] = list;
  if (plastic) {
    model["plastic"] = plastic_flow_json(*plastic);
  }
}

std::unique_ptr<Model> ScenePdeSurface::build() const {
  auto surface =
      std::make_unique<PdeSurface>(grid.grid(), grid.rest_positions(), material, regions);
  surface->set_plastic_flow(plastic);
  return surface;
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
ScenePdeSurface::naive_variant() const {
  if (regions.empty()) {
    return std::nullopt;
  }
  auto naive = std::make_unique<ScenePdeSurface>(*this);
  naive->regions.clear();
  return std::pair{std::unique_ptr<SceneModelSpec>(std::move(naive)),
                   std::string("deformation regions (naive: every grid node)")};
}

std::unique_ptr<SceneModelSpec> read_pde_surface_scene(const SceneReader& reader,
                                                       const JsonValue& model,
                                                       const std::string& path) {
  check_model_keys(reader, model, path, "pde_surface", {"grid", "regions", "plastic"});
  auto spec = std::make_unique<ScenePdeSurface>();
  spec->grid = read_scene_grid(reader, model, path);
  spec->plastic = read_plastic_flow(reader, model, path);
  const JsonValue material = model_material(
      reader, model, path, {"b", "c", "d", "density", "damping", "su0", "su1", "sv0", "sv1"});
  const std::string material_path = join_json_path(path, "material");
  PdeSurfaceMaterial& m = spec->material;
  reader.number_key(material, material_path, "b", m.b, 0.0, false);
  reader.number_key(material, material_path, "c", m.c, 0.0, false);
  reader.number_key(material, material_path, "d", m.d, 0.0, false);
  reader.number_key(material, material_path, "density", m.mass_density, 0.0, true);
  reader.number_key(material, material_path, "damping", m.damping_density, 0.0, false);
  reader.number_key(material, material_path, "su0", m.tangent_u0);
  reader.number_key(material, material_path, "su1", m.tangent_u1);
  reader.number_key(material, material_path, "sv0", m.tangent_v0);
  reader.number_key(material, material_path, "sv1", m.tangent_v1);
  if (const JsonValue* regions = reader.find(model, "regions")) {
    const std::string regions_path = join_json_path(path, "regions");
    reader.array(*regions, regions_path, "{\"centre\": [x, y, z], \"radius\": r} regions");
    for (size_t r = 0; r < regions->size(); ++r) {
      const std::string region_path = json_index_path(regions_path, r);
      const JsonValue& region = (*regions)[r];
      reader.object(region, region_path, {"centre", "radius"});
      DeformationRegion result;
      result.centre = reader.point(reader.require(region, region_path, "centre", "[x, y, z]"),
                                   join_json_path(region_path, "centre"));
      result.deformation_radius =
          reader.bounded(reader.require(region, region_path, "radius", "a radius > 0"),
                         join_json_path(region_path, "radius"), 0.0, true);
      spec->regions.push_back(result);
    }
  }
  return spec;
}

}  // namespace dnurbs
