#include "dnurbs/sculpt/sculpt_scene.h"

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dnurbs {
namespace {

using Json = nlohmann::json;

bool is_curve(const std::string& type) {
  return type == "dnurbs_curve";
}

// The material keys a setting writes for a model type ({} for stiffness and dt).
std::vector<const char*> material_keys(SculptSetting setting, bool curve) {
  switch (setting) {
    case SculptSetting::kTension:
      return curve ? std::vector<const char*>{"tension"} : std::vector<const char*>{"a10", "a01"};
    case SculptSetting::kRigidity:
      return curve ? std::vector<const char*>{"rigidity"}
                   : std::vector<const char*>{"b20", "b11", "b02"};
    case SculptSetting::kDensity:
      return {"mass_density"};
    case SculptSetting::kDamping:
      return {"damping_density"};
    default:
      return {};
  }
}

constexpr std::array<SculptSetting, 4> kMaterialSettings = {
    SculptSetting::kTension, SculptSetting::kRigidity, SculptSetting::kDensity,
    SculptSetting::kDamping};

}  // namespace

bool sculpt_material_applies(const SceneModel& model) {
  const std::string type = scene_model_type(model);
  return type == "dnurbs_curve" || type == "dnurbs_surface" || type == "triangular_dnurbs_surface";
}

SculptSettingOverrides sculpt_scene_settings(const Scene& scene) {
  SculptSettingOverrides values;
  values[static_cast<std::size_t>(SculptSetting::kDt)] = scene.integrator.dt;
  const Json json = Json::parse(scene_to_json(scene));
  for (std::size_t i = 0; i < scene.models.size(); ++i) {
    if (!sculpt_material_applies(scene.models[i])) {
      continue;
    }
    const Json& model = json["models"][i];
    const bool curve = is_curve(model.value("type", ""));
    const Json material = model.value("material", Json::object());
    for (const SculptSetting setting : kMaterialSettings) {
      const char* key = material_keys(setting, curve).front();
      if (material.contains(key) && material[key].is_number()) {
        values[static_cast<std::size_t>(setting)] = material[key].get<double>();
      }
    }
    break;
  }
  return values;
}

Scene sculpt_scene(const Scene& scene, const SculptSettingOverrides& overrides,
                   const std::vector<SculptPin>& pins) {
  Json json = Json::parse(scene_to_json(scene));
  if (const auto& dt = overrides[static_cast<std::size_t>(SculptSetting::kDt)]) {
    json["integrator"]["dt"] = *dt;
  }
  for (std::size_t i = 0; i < scene.models.size(); ++i) {
    if (!sculpt_material_applies(scene.models[i])) {
      continue;
    }
    Json& model = json["models"][i];
    const bool curve = is_curve(model.value("type", ""));
    for (const SculptSetting setting : kMaterialSettings) {
      if (const auto& value = overrides[static_cast<std::size_t>(setting)]) {
        for (const char* key : material_keys(setting, curve)) {
          model["material"][key] = *value;
        }
      }
    }
  }
  for (const SculptPin& pin : pins) {
    // [u, v]: curves read u and ignore v
    json["constraints"].push_back({{"type", "point_target"},
                                   {"model", pin.model},
                                   {"at", {pin.at.x(), pin.at.y()}},
                                   {"target", {pin.target.x(), pin.target.y(), pin.target.z()}}});
  }
  return parse_scene_json(json.dump(), scene.source, scene.directory);
}

}  // namespace dnurbs
