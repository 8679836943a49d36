#include "dnurbs/io/models/pde_surface_scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "dnurbs/dynamics/grid/pde_force_region.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {

namespace {

// The material keys in the order of pde_material_parameters, with their ranges.
struct MaterialKey {
  const char* name;
  std::optional<double> minimum;  // none: any finite number
  bool strict;
};
constexpr std::array<MaterialKey, kPdeMaterialParameterCount> kMaterialKeys{
    {{"b", 0.0, false},
     {"c", 0.0, false},
     {"d", 0.0, false},
     {"density", 0.0, true},
     {"damping", 0.0, false},
     {"su0", {}, false},
     {"su1", {}, false},
     {"sv0", {}, false},
     {"sv1", {}, false}}};
constexpr int kMaxFrame = 100000000;  // as run.steps

bool in_range(const MaterialKey& key, double value) {
  return std::isfinite(value) &&
         (!key.minimum || (key.strict ? value > *key.minimum : value >= *key.minimum));
}

// A material key: a number or keyframes (io/schedule.h), every value in the key's range.
void read_material_key(const SceneReader& reader, const JsonValue& material,
                       const std::string& path, const MaterialKey& key, ScalarSchedule& schedule) {
  const JsonValue* value = reader.find(material, key.name);
  if (value == nullptr) {
    return;
  }
  const std::string key_path = join_json_path(path, key.name);
  schedule = reader.scalar_schedule(*value, key_path);
  if (!key.minimum) {
    return;
  }
  if (value->is_number()) {
    reader.bounded(*value, key_path, *key.minimum, key.strict);
    return;
  }
  const std::string values_path = join_json_path(key_path, "values");
  for (size_t i = 0; i < schedule.values.size(); ++i) {
    reader.bounded((*value)["values"][i], json_index_path(values_path, i), *key.minimum,
                   key.strict);
  }
}

// "reset": a frame or an array of strictly increasing frames, each >= 1.
std::vector<int> read_reset_frames(const SceneReader& reader, const JsonValue& reset,
                                   const std::string& path) {
  if (!reset.is_array()) {
    return {reader.integer(reset, path, 1, kMaxFrame)};
  }
  std::vector<int> frames;
  for (size_t i = 0; i < reset.size(); ++i) {
    const std::string frame_path = json_index_path(path, i);
    frames.push_back(reader.integer(reset[i], frame_path, 1, kMaxFrame));
    if (i > 0 && frames[i] <= frames[i - 1]) {
      reader.fail(frame_path, "expected strictly increasing reset frames, got " +
                                  std::to_string(frames[i]) + " after " +
                                  std::to_string(frames[i - 1]));
    }
  }
  return frames;
}

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
  JsonOut keys = JsonOut::object();
  for (size_t k = 0; k < kMaterialKeys.size(); ++k) {
    keys[kMaterialKeys[k].name] = schedule_json(material[k]);
  }
  model["material"] = keys;
  if (start_frame != 0) {
    model["start_frame"] = start_frame;
  }
  if (!reset_frames.empty()) {
    model["reset"] = reset_frames;
  }
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
  auto surface = std::make_unique<PdeSurface>(grid.grid(), grid.rest_positions(), material_at(0.0),
                                              deformation_regions());
  surface->set_plastic_flow(plastic);
  return surface;
}

PdeSurfaceMaterial ScenePdeSurface::material_at(double time) const {
  Eigen::VectorXd values(kPdeMaterialParameterCount);
  for (size_t k = 0; k < material.size(); ++k) {
    values(static_cast<Eigen::Index>(k)) = material[k].at(time);
  }
  return pde_material_from_parameters(values);
}

SceneModelControls ScenePdeSurface::controls() const {
  SceneModelControls controls;
  controls.start_frame = start_frame;
  controls.reset_frames = reset_frames;
  if (std::none_of(material.begin(), material.end(),
                   [](const ScalarSchedule& key) { return !key.times.empty(); })) {
    return controls;
  }
  std::vector<ScalarOfTime> keys;  // the splines, built once
  keys.reserve(material.size());
  for (const ScalarSchedule& key : material) {
    keys.push_back(scalar_of_time(key));
  }
  controls.material = [keys = std::move(keys)](double time) {
    Eigen::VectorXd values(kPdeMaterialParameterCount);
    for (size_t k = 0; k < keys.size(); ++k) {
      const double value = keys[k](time);
      const MaterialKey& key = kMaterialKeys[k];
      if (!in_range(key, value)) {
        // A cubic spline ("interpolation": "cubic") through values in range can leave it
        // between keyframes (monotone and linear ones cannot); six digits: the time is a
        // product of steps, 0.040000000000000001 in full
        std::ostringstream text;
        text << "the keyframes give " << value << " at t = " << time << ", expected a number "
             << (key.strict ? "> " : ">= ") << *key.minimum
             << " (add a keyframe where the spline leaves the range)";
        throw SceneKeyError(std::string(".material.") + key.name, text.str());
      }
      values(static_cast<Eigen::Index>(k)) = value;
    }
    return values;
  };
  return controls;
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

std::array<ScalarSchedule, kPdeMaterialParameterCount> default_pde_material() {
  const Eigen::VectorXd values = pde_material_parameters(PdeSurfaceMaterial{});
  std::array<ScalarSchedule, kPdeMaterialParameterCount> material;
  for (size_t k = 0; k < material.size(); ++k) {
    material[k].values = {values(static_cast<Eigen::Index>(k))};
  }
  return material;
}

std::unique_ptr<SceneModelSpec> read_pde_surface_scene(const SceneReader& reader,
                                                       const JsonValue& model,
                                                       const std::string& path) {
  check_model_keys(reader, model, path, "pde_surface",
                   {"grid", "regions", "plastic", "start_frame", "reset"});
  auto spec = std::make_unique<ScenePdeSurface>();
  spec->grid = read_scene_grid(reader, model, path);
  spec->plastic = read_plastic_flow(reader, model, path);
  std::vector<const char*> names;
  names.reserve(kMaterialKeys.size());
  for (const MaterialKey& key : kMaterialKeys) {
    names.push_back(key.name);
  }
  const JsonValue material = model_material(reader, model, path, names);
  const std::string material_path = join_json_path(path, "material");
  for (size_t k = 0; k < kMaterialKeys.size(); ++k) {
    read_material_key(reader, material, material_path, kMaterialKeys[k], spec->material[k]);
  }
  reader.integer_key(model, path, "start_frame", spec->start_frame, 0, kMaxFrame);
  if (const JsonValue* reset = reader.find(model, "reset")) {
    spec->reset_frames = read_reset_frames(reader, *reset, join_json_path(path, "reset"));
  }
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
