#pragma once
// The one table of scene types: every model, force and constraint type of scene files with the
// function that reads its keys. The scene dispatcher (io/scene.cpp) finds a type here by its
// "type" string; nothing else in the library names a type. Adding a model type is one line in
// io/scene_model_types.def (docs/adding-a-model.md).

#include <memory>
#include <string>
#include <vector>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

/// Reads a model's keys at JSON path `path` (the "type" is already checked).
using SceneModelReader = std::unique_ptr<SceneModelSpec> (*)(const SceneReader& reader,
                                                             const JsonValue& model,
                                                             const std::string& path);
struct SceneModelType {
  const char* name;
  SceneModelReader read;
  bool border;           ///< boundary.clamp_border is allowed (Model::fix_border)
  bool points;           ///< boundary.fixed_points is allowed (Model::fix_point)
  bool local_sculpting;  ///< boundary.local_sculpting_margin is allowed (Model::freeze_outside)
};
/// Every model type: those of io/scene_model_types.def in its order, then the registered ones.
const std::vector<SceneModelType>& scene_model_types();
/// Adds a model type from outside the library (an application's own model): its scenes parse
/// and run like the built-in ones. Call it before parsing scenes (not thread-safe against
/// concurrent parsing); `type.name` must outlive every scene (a string literal). Throws Error
/// if the name is empty, taken or not [a-z0-9_]+, or the
/// reader is null.
void register_scene_model_type(const SceneModelType& type);

/// Reads a force's or a constraint's keys; model references resolve through `names`.
using SceneForceReader = std::unique_ptr<SceneForceSpec> (*)(const SceneReader& reader,
                                                             const ModelNames& names,
                                                             const JsonValue& force,
                                                             const std::string& path);
using SceneConstraintReader = std::unique_ptr<SceneConstraintSpec> (*)(const SceneReader& reader,
                                                                       const ModelNames& names,
                                                                       const JsonValue& constraint,
                                                                       const std::string& path);
struct SceneForceType {
  const char* name;
  SceneForceReader read;
};
struct SceneConstraintType {
  const char* name;
  SceneConstraintReader read;
};
const std::vector<SceneForceType>& scene_force_types();
const std::vector<SceneConstraintType>& scene_constraint_types();

/// The names of a table's types, in order (for "expected one of ..." messages).
template <typename Type>
std::vector<const char*> type_names(const std::vector<Type>& types) {
  std::vector<const char*> names;
  names.reserve(types.size());
  for (const Type& type : types) {
    names.push_back(type.name);
  }
  return names;
}

/// The entry of `types` named `name` (which the caller has checked against type_names).
template <typename Type>
const Type& find_type(const std::vector<Type>& types, const std::string& name) {
  for (const Type& type : types) {
    if (name == type.name) {
      return type;
    }
  }
  throw make_error("unknown scene type \"", name, "\"");
}

}  // namespace dnurbs
