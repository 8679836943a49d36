#include "dnurbs/io/models/pde_surface_scene.h"

#include "dnurbs/dynamics/grid/pde_force_region.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {

namespace {

JsonOut region_json(const ScenePdeRegion& region) {
  JsonOut json = JsonOut::object();
  if (region.box) {
    json["box"] = {{"min", json_array<3>(region.box->min())},
                   {"max", json_array<3>(region.box->max())}};
  } else {
    json["radius"] = region.radius;
  }
  if (!region.box || region.force_radius) {
    json["centre"] = schedule_json(region.centre);
  }
  if (region.force_radius) {
    json["force_radius"] = *region.force_radius;
    json["force"] = schedule_json(region.force);
  }
  return json;
}

ScenePdeRegion read_region(const SceneReader& reader, const JsonValue& region,
                           const std::string& path) {
  reader.object(region, path, {"centre", "radius", "box", "force_radius", "force"});
  ScenePdeRegion result;
  const JsonValue* box = reader.find(region, "box");
  const JsonValue* radius = reader.find(region, "radius");
  if ((box == nullptr) == (radius == nullptr)) {
    reader.fail(path, "a region needs exactly one of \"radius\" (with \"centre\") and \"box\"");
  }
  if (radius != nullptr) {
    result.radius = reader.bounded(*radius, join_json_path(path, "radius"), 0.0, true);
  } else {
    const std::string box_path = join_json_path(path, "box");
    reader.object(*box, box_path, {"min", "max"});
    const Eigen::Vector3d low = reader.point(reader.require(*box, box_path, "min", "[x, y, z]"),
                                             join_json_path(box_path, "min"));
    const Eigen::Vector3d high = reader.point(reader.require(*box, box_path, "max", "[x, y, z]"),
                                              join_json_path(box_path, "max"));
    if (!(low.array() <= high.array()).all()) {
      reader.fail(join_json_path(box_path, "max"),
                  "the box's max is below its min in some coordinate");
    }
    result.box = Eigen::AlignedBox3d(low, high);
  }
  const JsonValue* force_radius = reader.find(region, "force_radius");
  const JsonValue* force = reader.find(region, "force");
  if ((force_radius == nullptr) != (force == nullptr)) {
    reader.fail(join_json_path(path, force == nullptr ? "force_radius" : "force"),
                "a force region needs both \"force_radius\" and \"force\"");
  }
  if (force_radius != nullptr) {
    result.force_radius =
        reader.bounded(*force_radius, join_json_path(path, "force_radius"), 0.0, false);
    result.force = reader.vector_schedule(*force, join_json_path(path, "force"));
  }
  if (radius != nullptr || force_radius != nullptr) {
    result.centre =
        reader.vector_schedule(reader.require(region, path, "centre", "[x, y, z] or keyframes"),
                               join_json_path(path, "centre"));
  } else if (reader.find(region, "centre") != nullptr) {
    reader.fail(join_json_path(path, "centre"),
                "a box region uses \"centre\" only for its force region (add \"force_radius\")");
  }
  return result;
}

}  // namespace

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
  for (const ScenePdeRegion& region : regions) {
    list.push_back(region_json(region));
  }
  model["regions"] = list;
  if (plastic) {
    model["plastic"] = plastic_flow_json(*plastic);
  }
}

std::vector<DeformationRegion> ScenePdeSurface::deformation_regions() const {
  std::vector<DeformationRegion> result;
  if (whole_grid) {
    return result;
  }
  for (const ScenePdeRegion& region : regions) {
    if (region.box) {
      DeformationRegion box;
      box.box = region.box;
      result.push_back(box);
    } else if (region.centre.times.size() > 1) {
      // A moving region: the boxes it sweeps between its first and last keyframe, sampled
      // until the centre moves less than half a grid spacing between samples
      const std::vector<DeformationRegion> swept = swept_deformation_regions(
          vector_of_time(region.centre), region.radius, region.centre.times.front(),
          region.centre.times.back(), 0.5 * grid.grid().spacing());
      result.insert(result.end(), swept.begin(), swept.end());
    } else {
      result.push_back({region.centre.at(0.0), region.radius});
    }
  }
  return result;
}

std::unique_ptr<Model> ScenePdeSurface::build() const {
  auto surface = std::make_unique<PdeSurface>(grid.grid(), grid.rest_positions(), material,
                                              deformation_regions());
  surface->set_plastic_flow(plastic);
  return surface;
}

void ScenePdeSurface::add_model_forces(System& system, int model) const {
  for (const ScenePdeRegion& region : regions) {
    if (region.force_radius) {
      system.add_force(model, pde_force_region(system.model(model), vector_of_time(region.centre),
                                               *region.force_radius, vector_of_time(region.force)));
    }
  }
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
ScenePdeSurface::naive_variant() const {
  if (regions.empty() || whole_grid) {
    return std::nullopt;
  }
  auto naive = std::make_unique<ScenePdeSurface>(*this);
  naive->whole_grid = true;
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
    reader.array(*regions, regions_path,
                 "{\"centre\": [x, y, z], \"radius\": r} or {\"box\": {\"min\", \"max\"}} regions");
    for (size_t r = 0; r < regions->size(); ++r) {
      spec->regions.push_back(read_region(reader, (*regions)[r], json_index_path(regions_path, r)));
    }
  }
  return spec;
}

}  // namespace dnurbs
