#include "dnurbs/io/scene_forces.h"

#include <string>

#include "dnurbs/dynamics/core/forces.h"

namespace dnurbs {
namespace {

Eigen::Vector2d required_parameter(const SceneReader& reader, const JsonValue& value,
                                   const std::string& path) {
  return reader.parameter(reader.require(value, path, "at", "a material parameter [u, v]"),
                          join_json_path(path, "at"));
}

VectorSchedule required_vector_schedule(const SceneReader& reader, const JsonValue& value,
                                        const std::string& path, const char* key) {
  return reader.vector_schedule(reader.require(value, path, key, "[x, y, z] or keyframes"),
                                join_json_path(path, key));
}

}  // namespace

// point ------------------------------------------------------------------------------------------

std::unique_ptr<SceneForceSpec> ScenePointForce::clone() const {
  return std::make_unique<ScenePointForce>(*this);
}

void ScenePointForce::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model", model},
          {"at", parameter_json(at)},
          {"force", schedule_json(force)}};
}

void ScenePointForce::apply(System& system, double start, double end) const {
  system.add_force(model, windowed(point_force(at, vector_of_time(force)), start, end));
}

bool ScenePointForce::add_to_region(int index, SculptedRegion& region) const {
  if (model == index) {
    region.parameters.push_back(at);
  }
  return false;
}

std::unique_ptr<SceneForceSpec> read_point_force(const SceneReader& reader, const ModelNames& names,
                                                 const JsonValue& force, const std::string& path) {
  reader.object(force, path, {"type", "model", "at", "force", "start", "end"});
  auto spec = std::make_unique<ScenePointForce>();
  spec->model = names.require(reader, force, path, "model");
  spec->at = required_parameter(reader, force, path);
  spec->force = required_vector_schedule(reader, force, path, "force");
  return spec;
}

// spring -----------------------------------------------------------------------------------------

std::unique_ptr<SceneForceSpec> SceneSpringForce::clone() const {
  return std::make_unique<SceneSpringForce>(*this);
}

void SceneSpringForce::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model", model},
          {"at", parameter_json(at)},
          {"stiffness", stiffness},
          {"target", schedule_json(target)}};
}

void SceneSpringForce::apply(System& system, double start, double end) const {
  // Implicit: the spring's stiffness enters the integrators' step matrix (dynamics/core/spring.h)
  system.add_spring(
      model, windowed_spring(mouse_spring(at, vector_of_time(target), stiffness), start, end));
}

bool SceneSpringForce::add_to_region(int index, SculptedRegion& region) const {
  if (model == index) {
    region.parameters.push_back(at);
  }
  return false;
}

std::unique_ptr<SceneForceSpec> read_spring_force(const SceneReader& reader,
                                                  const ModelNames& names, const JsonValue& force,
                                                  const std::string& path) {
  reader.object(force, path, {"type", "model", "at", "stiffness", "target", "start", "end"});
  auto spec = std::make_unique<SceneSpringForce>();
  spec->model = names.require(reader, force, path, "model");
  spec->at = required_parameter(reader, force, path);
  spec->stiffness = reader.bounded(reader.require(force, path, "stiffness", "a stiffness >= 0"),
                                   join_json_path(path, "stiffness"), 0.0, false);
  spec->target = required_vector_schedule(reader, force, path, "target");
  return spec;
}

// control_point ----------------------------------------------------------------------------------

std::unique_ptr<SceneForceSpec> SceneControlPointForce::clone() const {
  return std::make_unique<SceneControlPointForce>(*this);
}

void SceneControlPointForce::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model", model},
          {"control_points", control_points},
          {"force", schedule_json(force)}};
}

void SceneControlPointForce::apply(System& system, double start, double end) const {
  const Model& target = system.model(model);
  for (size_t k = 0; k < control_points.size(); ++k) {
    const int index = control_points[k];
    try {
      const int offset = target.control_point_offset(index);
      if (offset + 3 > target.velocity_count()) {
        throw make_error("control point ", index, " does not exist");
      }
    } catch (const Error& error) {
      throw SceneKeyError(".control_points[" + std::to_string(k) + "]", error.what());
    }
  }
  system.add_force(
      model, windowed(control_point_force(control_points, vector_of_time(force)), start, end));
}

bool SceneControlPointForce::add_to_region(int index, SculptedRegion& region) const {
  if (model == index) {
    region.control_points.insert(region.control_points.end(), control_points.begin(),
                                 control_points.end());
  }
  return false;
}

std::unique_ptr<SceneForceSpec> read_control_point_force(const SceneReader& reader,
                                                         const ModelNames& names,
                                                         const JsonValue& force,
                                                         const std::string& path) {
  reader.object(force, path, {"type", "model", "control_points", "force", "start", "end"});
  auto spec = std::make_unique<SceneControlPointForce>();
  spec->model = names.require(reader, force, path, "model");
  spec->control_points = reader.indices(
      reader.require(force, path, "control_points", "an array of control point indices"),
      join_json_path(path, "control_points"));
  spec->force = required_vector_schedule(reader, force, path, "force");
  return spec;
}

// gravity ----------------------------------------------------------------------------------------

std::unique_ptr<SceneForceSpec> SceneGravity::clone() const {
  return std::make_unique<SceneGravity>(*this);
}

void SceneGravity::write(JsonOut& json) const {
  json = {{"type", type()}};
  if (model >= 0) {
    json["model"] = model;
  }
  json["acceleration"] = json_array<3>(acceleration);
}

void SceneGravity::apply(System& system, double start, double end) const {
  for (int m = 0; m < system.model_count(); ++m) {
    if (model < 0 || model == m) {
      system.add_force(m, windowed(gravity(acceleration), start, end));
    }
  }
}

bool SceneGravity::add_to_region(int index, SculptedRegion& /*region*/) const {
  return model == -1 || model == index;
}

std::unique_ptr<SceneForceSpec> read_gravity(const SceneReader& reader, const ModelNames& names,
                                             const JsonValue& force, const std::string& path) {
  reader.object(force, path, {"type", "model", "acceleration", "start", "end"});
  auto spec = std::make_unique<SceneGravity>();
  if (const JsonValue* model = reader.find(force, "model")) {
    spec->model = names.resolve(reader, *model, join_json_path(path, "model"));
  }
  if (const JsonValue* g = reader.find(force, "acceleration")) {
    spec->acceleration = reader.point(*g, join_json_path(path, "acceleration"));
  }
  return spec;
}

// pressure ---------------------------------------------------------------------------------------

std::unique_ptr<SceneForceSpec> ScenePressure::clone() const {
  return std::make_unique<ScenePressure>(*this);
}

void ScenePressure::write(JsonOut& json) const {
  json = {{"type", type()}, {"model", model}, {"pressure", schedule_json(pressure)}};
}

void ScenePressure::apply(System& system, double start, double end) const {
  system.add_force(model, windowed(dnurbs::pressure(scalar_of_time(pressure)), start, end));
}

bool ScenePressure::add_to_region(int index, SculptedRegion& /*region*/) const {
  return model == index;
}

std::unique_ptr<SceneForceSpec> read_pressure(const SceneReader& reader, const ModelNames& names,
                                              const JsonValue& force, const std::string& path) {
  reader.object(force, path, {"type", "model", "pressure", "start", "end"});
  auto spec = std::make_unique<ScenePressure>();
  spec->model = names.require(reader, force, path, "model");
  spec->pressure =
      reader.scalar_schedule(reader.require(force, path, "pressure", "a number or keyframes"),
                             join_json_path(path, "pressure"));
  return spec;
}

// wind -------------------------------------------------------------------------------------------

std::unique_ptr<SceneForceSpec> SceneWind::clone() const {
  return std::make_unique<SceneWind>(*this);
}

void SceneWind::write(JsonOut& json) const {
  json = {{"type", type()}};
  if (model >= 0) {
    json["model"] = model;
  }
  json["velocity"] = schedule_json(velocity);
  json["drag"] = drag;
}

void SceneWind::apply(System& system, double start, double end) const {
  if (model >= 0 && system.model(model).parametric_dimension() != 2) {
    throw SceneKeyError(".model", make_error("expected a surface model: model ", model,
                                             " is a curve, which feels no wind")
                                      .what());
  }
  for (int m = 0; m < system.model_count(); ++m) {
    if ((model < 0 && system.model(m).parametric_dimension() == 2) || model == m) {
      system.add_force(m, windowed(wind(vector_of_time(velocity), drag), start, end));
    }
  }
}

bool SceneWind::add_to_region(int index, SculptedRegion& /*region*/) const {
  return model == -1 || model == index;
}

std::unique_ptr<SceneForceSpec> read_wind(const SceneReader& reader, const ModelNames& names,
                                          const JsonValue& force, const std::string& path) {
  reader.object(force, path, {"type", "model", "velocity", "drag", "start", "end"});
  auto spec = std::make_unique<SceneWind>();
  if (const JsonValue* model = reader.find(force, "model")) {
    spec->model = names.resolve(reader, *model, join_json_path(path, "model"));
  }
  spec->velocity = required_vector_schedule(reader, force, path, "velocity");
  spec->drag = reader.bounded(reader.require(force, path, "drag", "a drag coefficient >= 0"),
                              join_json_path(path, "drag"), 0.0, false);
  return spec;
}

}  // namespace dnurbs
