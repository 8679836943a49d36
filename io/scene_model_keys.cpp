#include "dnurbs/io/scene_model_keys.h"

#include <vector>

namespace dnurbs {

void check_model_keys(const SceneReader& reader, const JsonValue& model, const std::string& path,
                      const std::string& type, std::initializer_list<const char*> own) {
  std::vector<const char*> all = {"type", "name", "material", "boundary", "resolution_scale"};
  all.insert(all.end(), own);
  reader.object(model, path, all, "a " + type + " model");
}

JsonValue model_material(const SceneReader& reader, const JsonValue& model, const std::string& path,
                         const std::vector<const char*>& allowed) {
  const JsonValue* material = reader.find(model, "material");
  JsonValue result = material != nullptr ? *material : JsonValue::object();
  reader.object(result, join_json_path(path, "material"), allowed, "");
  return result;
}

std::optional<SceneFit> read_fit(const SceneReader& reader, const JsonValue& model,
                                 const std::string& path, bool dnurbs,
                                 std::initializer_list<const char*> instead_of) {
  const JsonValue* value = reader.find(model, "fit");
  if (value == nullptr) {
    return std::nullopt;
  }
  const std::string fit_path = join_json_path(path, "fit");
  for (const char* key : instead_of) {
    if (reader.find(model, key) != nullptr) {
      reader.fail(fit_path, std::string("expected either \"fit\" or \"") + key +
                                "\", not both (the fit gives the initial shape)");
    }
  }
  if (dnurbs) {
    reader.object(*value, fit_path, {"points", "degree", "spans", "smoothness", "iterations"});
  } else {
    reader.object(*value, fit_path, {"points", "max_evaluations", "twist", "shear", "bend_shape"});
  }
  SceneFit fit;
  fit.points =
      reader.string(reader.require(*value, fit_path, "points", "a file of points or a mesh"),
                    join_json_path(fit_path, "points"));
  reader.integer_key(*value, fit_path, "degree", fit.degree, 1, 9);
  reader.integer_key(*value, fit_path, "spans", fit.spans, 1, 1000);
  reader.number_key(*value, fit_path, "smoothness", fit.smoothness, 0.0, false);
  reader.integer_key(*value, fit_path, "iterations", fit.iterations, 1, 100000);
  reader.integer_key(*value, fit_path, "max_evaluations", fit.max_evaluations, 1, 100000000);
  reader.boolean_key(*value, fit_path, "twist", fit.twist);
  reader.boolean_key(*value, fit_path, "shear", fit.shear);
  reader.boolean_key(*value, fit_path, "bend_shape", fit.bend_shape);
  return fit;
}

JsonOut fit_json(const SceneFit& fit, bool dnurbs) {
  JsonOut json;
  json["points"] = fit.points;
  if (dnurbs) {
    json["degree"] = fit.degree;
    json["spans"] = fit.spans;
    json["smoothness"] = fit.smoothness;
    json["iterations"] = fit.iterations;
  } else {
    json["max_evaluations"] = fit.max_evaluations;
    json["twist"] = fit.twist;
    json["shear"] = fit.shear;
    json["bend_shape"] = fit.bend_shape;
  }
  return json;
}

std::optional<PlasticFlow> read_plastic_flow(const SceneReader& reader, const JsonValue& model,
                                             const std::string& path) {
  const JsonValue* plastic = reader.find(model, "plastic");
  if (plastic == nullptr) {
    return std::nullopt;
  }
  const std::string plastic_path = join_json_path(path, "plastic");
  reader.object(*plastic, plastic_path, {"yield", "rate"});
  PlasticFlow flow;
  reader.number_key(*plastic, plastic_path, "yield", flow.yield, 0.0, false);
  reader.number_key(*plastic, plastic_path, "rate", flow.rate, 0.0, true);
  return flow;
}

JsonOut plastic_flow_json(const PlasticFlow& flow) {
  return {{"yield", flow.yield}, {"rate", flow.rate}};
}

void read_rest_shape_keys(const SceneReader& reader, const JsonValue& model,
                          const std::string& path, bool& initial_shape_at_rest,
                          std::optional<PlasticFlow>& plastic_flow) {
  const JsonValue* rest = reader.find(model, "rest_shape");
  if (rest != nullptr) {
    initial_shape_at_rest =
        reader.choice(*rest, join_json_path(path, "rest_shape"), {"none", "initial"}) == "initial";
  }
  plastic_flow = read_plastic_flow(reader, model, path);
  if (plastic_flow && rest != nullptr && !initial_shape_at_rest) {
    // The yield rule moves a rest shape: "none" leaves it none to move
    reader.fail(join_json_path(path, "plastic"),
                "a plastic rest shape needs \"rest_shape\": \"initial\"");
  }
}

void write_rest_shape_keys(bool initial_shape_at_rest,
                           const std::optional<PlasticFlow>& plastic_flow, JsonOut& model) {
  if (initial_shape_at_rest) {
    model["rest_shape"] = "initial";
  }
  if (plastic_flow) {
    model["plastic"] = plastic_flow_json(*plastic_flow);
  }
}

}  // namespace dnurbs
