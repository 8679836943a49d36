#include "dnurbs/io/scene_constraints.h"

#include <string>
#include <utility>

#include "dnurbs/constraints/curve_on_surface_constraint.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/constraints/surface_constraints.h"
#include "dnurbs/io/json_messages.h"

// Each constraint type's keys are read by read_keys, written by write_keys (after "type"),
// turned into library constraints by add_constraints and into the parameters of local sculpting
// by add_region (true: the constraint needs the whole model). The overloads are grouped by what
// they do.

namespace dnurbs {
namespace {

Eigen::Vector2d required_parameter(const SceneReader& reader, const JsonValue& value,
                                   const std::string& path, const char* key) {
  return reader.parameter(reader.require(value, path, key, "a material parameter [u, v]"),
                          join_json_path(path, key));
}

Eigen::Vector3d required_point(const SceneReader& reader, const JsonValue& value,
                               const std::string& path, const char* key) {
  return reader.point(reader.require(value, path, key, "[x, y, z]"), join_json_path(path, key));
}

// An axis: two material parameters [[u, v], [u, v]].
void read_axis(const SceneReader& reader, const JsonValue& value, const std::string& path,
               const char* key, Eigen::Vector2d& a0, Eigen::Vector2d& a1) {
  const std::string axis_path = join_json_path(path, key);
  const JsonValue& pair =
      reader.require(value, path, key, "two material parameters [[u, v], [u, v]]");
  if (!pair.is_array() || pair.size() != 2) {
    reader.fail(axis_path, "expected two material parameters [[u, v], [u, v]], got " +
                               describe_json_value(pair));
  }
  a0 = reader.parameter(pair[0], json_index_path(axis_path, 0));
  a1 = reader.parameter(pair[1], json_index_path(axis_path, 1));
}

// The material parameters held on model `model`, when it is the model `index`.
void add_parameters(int model, int index, std::initializer_list<Eigen::Vector2d> at,
                    SculptedRegion& region) {
  if (model == index) {
    region.parameters.insert(region.parameters.end(), at);
  }
}

}  // namespace

// Readers ----------------------------------------------------------------------------------------

void read_keys(const SceneReader& reader, const ModelNames& names, const JsonValue& constraint,
               const std::string& path, PointTargetKeys& keys) {
  reader.object(constraint, path, {"type", "model", "at", "target", "alpha", "beta"});
  keys.model = names.require(reader, constraint, path, "model");
  keys.at = required_parameter(reader, constraint, path, "at");
  keys.target =
      reader.vector_schedule(reader.require(constraint, path, "target", "[x, y, z] or keyframes"),
                             join_json_path(path, "target"));
}

void read_keys(const SceneReader& reader, const ModelNames& names, const JsonValue& constraint,
               const std::string& path, PointToPointKeys& keys) {
  reader.object(constraint, path, {"type", "model_a", "at_a", "model_b", "at_b", "alpha", "beta"});
  keys.model_a = names.require(reader, constraint, path, "model_a");
  keys.at_a = required_parameter(reader, constraint, path, "at_a");
  keys.model_b = names.require(reader, constraint, path, "model_b");
  keys.at_b = required_parameter(reader, constraint, path, "at_b");
}

void read_keys(const SceneReader& reader, const ModelNames& names, const JsonValue& constraint,
               const std::string& path, HingeKeys& keys) {
  reader.object(constraint, path,
                {"type", "model_a", "axis_a", "model_b", "axis_b", "alpha", "beta"});
  keys.model_a = names.require(reader, constraint, path, "model_a");
  read_axis(reader, constraint, path, "axis_a", keys.axis_a0, keys.axis_a1);
  keys.model_b = names.require(reader, constraint, path, "model_b");
  read_axis(reader, constraint, path, "axis_b", keys.axis_b0, keys.axis_b1);
}

void read_keys(const SceneReader& reader, const ModelNames& names, const JsonValue& constraint,
               const std::string& path, ControlPointKeys& keys) {
  reader.object(constraint, path, {"type", "model", "control_point", "target", "alpha", "beta"});
  keys.model = names.require(reader, constraint, path, "model");
  keys.control_point =
      reader.integer(reader.require(constraint, path, "control_point", "a control point index"),
                     join_json_path(path, "control_point"), 0, 1 << 30);
  keys.target = required_point(reader, constraint, path, "target");
}

void read_keys(const SceneReader& reader, const ModelNames& names, const JsonValue& constraint,
               const std::string& path, SurfaceNormalKeys& keys) {
  reader.object(constraint, path, {"type", "model", "at", "direction", "alpha", "beta"});
  keys.model = names.require(reader, constraint, path, "model");
  keys.at = required_parameter(reader, constraint, path, "at");
  keys.direction = required_point(reader, constraint, path, "direction");
  if (!(keys.direction.norm() > 0.0)) {
    reader.fail(join_json_path(path, "direction"), "expected a non-zero direction");
  }
}

void read_keys(const SceneReader& reader, const ModelNames& names, const JsonValue& constraint,
               const std::string& path, CurveOnSurfaceKeys& keys) {
  reader.object(constraint, path,
                {"type", "curve_model", "surface_model", "samples", "follow", "alpha", "beta"});
  keys.curve_model = names.require(reader, constraint, path, "curve_model");
  keys.surface_model = names.require(reader, constraint, path, "surface_model");
  reader.integer_key(constraint, path, "samples", keys.samples, 1, 10000);
  reader.boolean_key(constraint, path, "follow", keys.follow);
  if (keys.follow && keys.samples < 2) {
    reader.fail(join_json_path(path, "samples"),
                "a curve following the surface needs at least 2 samples, got " +
                    std::to_string(keys.samples));
  }
}

// Writers ----------------------------------------------------------------------------------------

void write_keys(const PointTargetKeys& keys, JsonOut& json) {
  json["model"] = keys.model;
  json["at"] = parameter_json(keys.at);
  json["target"] = schedule_json(keys.target);
}

void write_keys(const PointToPointKeys& keys, JsonOut& json) {
  json["model_a"] = keys.model_a;
  json["at_a"] = parameter_json(keys.at_a);
  json["model_b"] = keys.model_b;
  json["at_b"] = parameter_json(keys.at_b);
}

void write_keys(const HingeKeys& keys, JsonOut& json) {
  json["model_a"] = keys.model_a;
  json["axis_a"] = {parameter_json(keys.axis_a0), parameter_json(keys.axis_a1)};
  json["model_b"] = keys.model_b;
  json["axis_b"] = {parameter_json(keys.axis_b0), parameter_json(keys.axis_b1)};
}

void write_keys(const ControlPointKeys& keys, JsonOut& json) {
  json["model"] = keys.model;
  json["control_point"] = keys.control_point;
  json["target"] = json_array<3>(keys.target);
}

void write_keys(const SurfaceNormalKeys& keys, JsonOut& json) {
  json["model"] = keys.model;
  json["at"] = parameter_json(keys.at);
  json["direction"] = json_array<3>(keys.direction);
}

void write_keys(const CurveOnSurfaceKeys& keys, JsonOut& json) {
  json["curve_model"] = keys.curve_model;
  json["surface_model"] = keys.surface_model;
  json["samples"] = keys.samples;
  if (keys.follow) {
    json["follow"] = true;
  }
}

// Library constraints ----------------------------------------------------------------------------

void add_constraints(const PointTargetKeys& keys, ConstraintSolver& solver, System& system,
                     const BaumgarteParameters& parameters) {
  solver.add(system, PointTargetConstraint(keys.model, keys.at, trajectory(keys.target)),
             parameters);
}

void add_constraints(const PointToPointKeys& keys, ConstraintSolver& solver, System& system,
                     const BaumgarteParameters& parameters) {
  solver.add(system, PointToPointConstraint(keys.model_a, keys.at_a, keys.model_b, keys.at_b),
             parameters);
}

void add_constraints(const HingeKeys& keys, ConstraintSolver& solver, System& system,
                     const BaumgarteParameters& parameters) {
  solver.add(system,
             HingeConstraint(keys.model_a, keys.axis_a0, keys.axis_a1, keys.model_b, keys.axis_b0,
                             keys.axis_b1),
             parameters);
}

void add_constraints(const ControlPointKeys& keys, ConstraintSolver& solver, System& system,
                     const BaumgarteParameters& parameters) {
  solver.add(system, ControlPointConstraint(keys.model, keys.control_point, keys.target),
             parameters);
}

void add_constraints(const SurfaceNormalKeys& keys, ConstraintSolver& solver, System& system,
                     const BaumgarteParameters& parameters) {
  solver.add(system, SurfaceNormalConstraint(keys.model, keys.at, keys.direction), parameters);
}

void add_constraints(const CurveOnSurfaceKeys& keys, ConstraintSolver& solver, System& system,
                     const BaumgarteParameters& parameters) {
  if (keys.follow) {
    solver.add(
        system,
        evenly_sampled_curve_on_surface(system, keys.curve_model, keys.surface_model, keys.samples),
        parameters);
    return;
  }
  for (auto& constraint :
       curve_on_surface_constraints(system, keys.curve_model, keys.surface_model, keys.samples)) {
    solver.add(system, std::move(constraint), parameters);
  }
}

// Regions of local sculpting ---------------------------------------------------------------------

bool add_region(const PointTargetKeys& keys, int index, SculptedRegion& region) {
  add_parameters(keys.model, index, {keys.at}, region);
  return false;
}

bool add_region(const PointToPointKeys& keys, int index, SculptedRegion& region) {
  add_parameters(keys.model_a, index, {keys.at_a}, region);
  add_parameters(keys.model_b, index, {keys.at_b}, region);
  return false;
}

bool add_region(const HingeKeys& keys, int index, SculptedRegion& region) {
  add_parameters(keys.model_a, index, {keys.axis_a0, keys.axis_a1}, region);
  add_parameters(keys.model_b, index, {keys.axis_b0, keys.axis_b1}, region);
  return false;
}

bool add_region(const ControlPointKeys& keys, int index, SculptedRegion& region) {
  if (keys.model == index) {
    region.control_points.push_back(keys.control_point);
  }
  return false;
}

bool add_region(const SurfaceNormalKeys& keys, int index, SculptedRegion& region) {
  add_parameters(keys.model, index, {keys.at}, region);
  return false;
}

bool add_region(const CurveOnSurfaceKeys& keys, int index, SculptedRegion& /*region*/) {
  return keys.curve_model == index || keys.surface_model == index;
}

// SceneConstraintOf ------------------------------------------------------------------------------

template <typename Keys>
void SceneConstraintOf<Keys>::write(JsonOut& json) const {
  json = {{"type", type()}};
  write_keys(static_cast<const Keys&>(*this), json);
}

template <typename Keys>
void SceneConstraintOf<Keys>::add(ConstraintSolver& solver, System& system,
                                  const BaumgarteParameters& parameters) const {
  add_constraints(static_cast<const Keys&>(*this), solver, system, parameters);
}

template <typename Keys>
bool SceneConstraintOf<Keys>::add_to_region(int index, SculptedRegion& region) const {
  return add_region(static_cast<const Keys&>(*this), index, region);
}

template <typename Keys>
std::unique_ptr<SceneConstraintSpec> SceneConstraintOf<Keys>::read(const SceneReader& reader,
                                                                   const ModelNames& names,
                                                                   const JsonValue& constraint,
                                                                   const std::string& path) {
  auto spec = std::make_unique<SceneConstraintOf>();
  read_keys(reader, names, constraint, path, static_cast<Keys&>(*spec));
  return spec;
}

template class SceneConstraintOf<PointTargetKeys>;
template class SceneConstraintOf<PointToPointKeys>;
template class SceneConstraintOf<HingeKeys>;
template class SceneConstraintOf<ControlPointKeys>;
template class SceneConstraintOf<SurfaceNormalKeys>;
template class SceneConstraintOf<CurveOnSurfaceKeys>;

}  // namespace dnurbs
