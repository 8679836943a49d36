#include "dnurbs/io/models/snake_scene.h"

#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {

std::unique_ptr<SceneModelSpec> SceneSnake::clone() const {
  return std::make_unique<SceneSnake>(*this);
}

void SceneSnake::write(JsonOut& model) const {
  JsonOut list = JsonOut::array();
  for (const auto& node : nodes) {
    list.push_back(json_array<3>(node));
  }
  model["nodes"] = list;
  model["closed"] = closed;
  model["material"] = {{"mass_density", material.mass_density},
                       {"damping_density", material.damping_density},
                       {"tension", material.constant_tension},
                       {"rigidity", material.constant_rigidity}};
}

std::unique_ptr<Model> SceneSnake::build() const {
  const NodeChain chain(static_cast<int>(nodes.size()), closed);
  NodePositions positions(static_cast<Eigen::Index>(nodes.size()), 3);
  for (size_t i = 0; i < nodes.size(); ++i) {
    positions.row(static_cast<Eigen::Index>(i)) = nodes[i].transpose();
  }
  return std::make_unique<Snake>(chain, positions, material);
}

std::unique_ptr<SceneModelSpec> read_snake_scene(const SceneReader& reader, const JsonValue& model,
                                                 const std::string& path) {
  check_model_keys(reader, model, path, "snake", {"nodes", "closed"});
  auto spec = std::make_unique<SceneSnake>();
  const std::string nodes_path = join_json_path(path, "nodes");
  const JsonValue& nodes = reader.array(
      reader.require(model, path, "nodes", "an array of [x, y, z]"), nodes_path, "[x, y, z] nodes");
  for (size_t i = 0; i < nodes.size(); ++i) {
    spec->nodes.push_back(reader.point(nodes[i], json_index_path(nodes_path, i)));
  }
  reader.boolean_key(model, path, "closed", spec->closed);
  const size_t minimum = spec->closed ? 4 : 3;
  if (spec->nodes.size() < minimum) {
    reader.fail(nodes_path, "expected at least " + std::to_string(minimum) + " nodes for " +
                                (spec->closed ? "a closed" : "an open") + " snake, got " +
                                std::to_string(spec->nodes.size()));
  }
  const JsonValue material = model_material(
      reader, model, path, {"mass_density", "damping_density", "tension", "rigidity"});
  const std::string material_path = join_json_path(path, "material");
  SnakeMaterial& m = spec->material;
  reader.number_key(material, material_path, "mass_density", m.mass_density, 0.0, true);
  reader.number_key(material, material_path, "damping_density", m.damping_density, 0.0, false);
  reader.number_key(material, material_path, "tension", m.constant_tension, 0.0, false);
  reader.number_key(material, material_path, "rigidity", m.constant_rigidity, 0.0, false);
  return spec;
}

}  // namespace dnurbs
