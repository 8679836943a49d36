#include "dnurbs/io/scene_registry.h"

#include "dnurbs/io/scene_constraints.h"
#include "dnurbs/io/scene_data_force.h"
#include "dnurbs/io/scene_forces.h"
#include "dnurbs/io/scene_image_force.h"

namespace dnurbs {

// The readers of io/scene_model_types.def, defined in io/models/.
#define DNURBS_SCENE_MODEL_TYPE(type, reader, border, points, local_sculpting) \
  std::unique_ptr<SceneModelSpec> reader(const SceneReader&, const JsonValue&, const std::string&);
#include "dnurbs/io/scene_model_types.def"
#undef DNURBS_SCENE_MODEL_TYPE

namespace {

std::vector<SceneModelType>& model_types() {
  static std::vector<SceneModelType> types = {
#define DNURBS_SCENE_MODEL_TYPE(type, reader, border, points, local_sculpting) \
  {#type, &(reader), border, points, local_sculpting},
#include "dnurbs/io/scene_model_types.def"
#undef DNURBS_SCENE_MODEL_TYPE
  };
  return types;
}

}  // namespace

const std::vector<SceneModelType>& scene_model_types() {
  return model_types();
}

void register_scene_model_type(const SceneModelType& type) {
  const std::string name = type.name != nullptr ? type.name : "";
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos) {
    throw make_error("scene model type name \"", name,
                     "\" is not a non-empty name of lower-case letters, digits and _");
  }
  if (type.read == nullptr) {
    throw make_error("scene model type \"", name, "\" has no reader");
  }
  for (const SceneModelType& existing : model_types()) {
    if (name == existing.name) {
      throw make_error("scene model type \"", name, "\" is already registered");
    }
  }
  model_types().push_back(type);
}

const std::vector<SceneForceType>& scene_force_types() {
  static const std::vector<SceneForceType> types = {
      {"point", &read_point_force},
      {"spring", &read_spring_force},
      {"control_point", &read_control_point_force},
      {"gravity", &read_gravity},
      {"pressure", &read_pressure},
      {"wind", &read_wind},
      {"image_potential", &read_image_potential},
      {"data_points", &read_data_points},
  };
  return types;
}

const std::vector<SceneConstraintType>& scene_constraint_types() {
  static const std::vector<SceneConstraintType> types = {
      {"point_target", &ScenePointTargetConstraint::read},
      {"point_to_point", &ScenePointToPointConstraint::read},
      {"hinge", &SceneHingeConstraint::read},
      {"control_point", &SceneControlPointConstraint::read},
      {"surface_normal", &SceneSurfaceNormalConstraint::read},
      {"curve_on_surface", &SceneCurveOnSurfaceConstraint::read},
  };
  return types;
}

}  // namespace dnurbs
