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
    reader.object(*value, fit_path, {"points", "max_evaluations"});
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
  }
  return json;
}

}  // namespace dnurbs
