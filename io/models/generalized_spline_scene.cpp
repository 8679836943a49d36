#include "dnurbs/io/models/generalized_spline_scene.h"

#include "dnurbs/core/error.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {

std::unique_ptr<SceneModelSpec> SceneGeneralizedSpline::clone() const {
  return std::make_unique<SceneGeneralizedSpline>(*this);
}

void SceneGeneralizedSpline::write(JsonOut& model) const {
  if (grid) {
    model["grid"] = scene_grid_json(*grid);
  } else {
    JsonOut list = JsonOut::array();
    for (const auto& node : nodes) {
      list.push_back(json_array<3>(node));
    }
    model["nodes"] = list;
    model["closed"] = closed;
  }
  model["order"] = material.order;
  if (terms_given) {
    JsonOut terms = JsonOut::array();
    for (const SplineTerm& term : material.terms) {
      JsonOut j = grid ? JsonOut::array({term.ju, term.jv}) : JsonOut::array({term.ju});
      JsonOut weight;
      if (term.node_weights.size() > 0) {
        weight = JsonOut::array();
        for (const double w : term.node_weights) {
          weight.push_back(w);
        }
      } else {
        weight = term.weight(Eigen::Vector2d::Zero());
      }
      terms.push_back({{"j", j}, {"weight", weight}});
    }
    model["terms"] = terms;
  }
  model["material"] = {{"mass_density", material.mass_density},
                       {"damping_density", material.damping_density}};
}

std::unique_ptr<Model> SceneGeneralizedSpline::build() const {
  if (grid) {
    return std::make_unique<GeneralizedSpline>(grid->grid(), grid->rest_positions(), material);
  }
  NodePositions positions(static_cast<Eigen::Index>(nodes.size()), 3);
  for (size_t i = 0; i < nodes.size(); ++i) {
    positions.row(static_cast<Eigen::Index>(i)) = nodes[i].transpose();
  }
  return std::make_unique<GeneralizedSpline>(NodeChain(static_cast<int>(nodes.size()), closed),
                                             positions, material);
}

namespace {

// One entry of "terms": {"j": [ju] (chains) or [ju, jv] (grids), "weight": w or [w per node]}.
SplineTerm read_term(const SceneReader& reader, const JsonValue& term, const std::string& path,
                     bool on_grid, size_t node_count) {
  reader.object(term, path, {"j", "weight"});
  SplineTerm result;
  const std::string j_path = join_json_path(path, "j");
  const JsonValue& j = reader.require(term, path, "j", on_grid ? "[ju, jv]" : "[ju]");
  if (!j.is_array() || j.size() != (on_grid ? 2U : 1U)) {
    reader.fail(j_path,
                std::string("expected ") + (on_grid ? "[ju, jv] on a grid" : "[ju] on a chain"));
  }
  result.ju = reader.integer(j[0], json_index_path(j_path, 0), 0, 16);
  result.jv = on_grid ? reader.integer(j[1], json_index_path(j_path, 1), 0, 16) : 0;
  if (const JsonValue* weight = reader.find(term, "weight")) {
    const std::string weight_path = join_json_path(path, "weight");
    if (weight->is_array()) {
      if (weight->size() != node_count) {
        reader.fail(weight_path, "expected " + std::to_string(node_count) +
                                     " weights (one per node), got " +
                                     std::to_string(weight->size()));
      }
      result.node_weights.resize(static_cast<Eigen::Index>(node_count));
      for (size_t k = 0; k < node_count; ++k) {
        result.node_weights[static_cast<Eigen::Index>(k)] =
            reader.bounded((*weight)[k], json_index_path(weight_path, k), 0.0, false);
      }
    } else {
      result.weight = reader.bounded(*weight, weight_path, 0.0, false);
    }
  }
  return result;
}

}  // namespace

std::unique_ptr<SceneModelSpec> read_generalized_spline_scene(const SceneReader& reader,
                                                              const JsonValue& model,
                                                              const std::string& path) {
  check_model_keys(reader, model, path, "generalized_spline",
                   {"nodes", "closed", "grid", "order", "terms"});
  auto spec = std::make_unique<SceneGeneralizedSpline>();
  const JsonValue* nodes = reader.find(model, "nodes");
  const JsonValue* grid = reader.find(model, "grid");
  if ((nodes == nullptr) == (grid == nullptr)) {
    reader.fail(path, nodes == nullptr
                          ? "missing key \"nodes\" (a chain) or \"grid\" (a grid)"
                          : "both \"nodes\" and \"grid\" given (expected one of them)");
  }
  size_t node_count = 0;
  if (grid != nullptr) {
    if (reader.find(model, "closed") != nullptr) {
      reader.fail(join_json_path(path, "closed"), "a grid is open (\"closed\" is for chains)");
    }
    spec->grid = read_scene_grid(reader, model, path);
    node_count = static_cast<size_t>(spec->grid->nodes_u) * spec->grid->nodes_v;
  } else {
    const std::string nodes_path = join_json_path(path, "nodes");
    reader.array(*nodes, nodes_path, "[x, y, z] nodes");
    for (size_t i = 0; i < nodes->size(); ++i) {
      spec->nodes.push_back(reader.point((*nodes)[i], json_index_path(nodes_path, i)));
    }
    reader.boolean_key(model, path, "closed", spec->closed);
    node_count = spec->nodes.size();
  }
  GeneralizedSplineMaterial& material = spec->material;
  reader.integer_key(model, path, "order", material.order, 1, 8);
  if (const JsonValue* terms = reader.find(model, "terms")) {
    const std::string terms_path = join_json_path(path, "terms");
    reader.array(*terms, terms_path, "terms {\"j\": ..., \"weight\": ...}");
    for (size_t k = 0; k < terms->size(); ++k) {
      material.terms.push_back(read_term(reader, (*terms)[k], json_index_path(terms_path, k),
                                         grid != nullptr, node_count));
    }
    spec->terms_given = true;
  }
  const JsonValue values = model_material(reader, model, path, {"mass_density", "damping_density"});
  const std::string material_path = join_json_path(path, "material");
  reader.number_key(values, material_path, "mass_density", material.mass_density, 0.0, false);
  reader.number_key(values, material_path, "damping_density", material.damping_density, 0.0, false);
  // The model checks the rest (orders of the terms, enough nodes, mu = gamma = 0): its message
  // names the value; the key is the model's.
  try {
    spec->build();
  } catch (const Error& error) {
    reader.fail(path, error.what());
  }
  return spec;
}

}  // namespace dnurbs
