#include "io/scene_constraints.h"

#include <utility>

#include "constraints/point_constraints.h"
#include "constraints/surface_constraints.h"
#include "io/json_messages.h"

namespace dnurbs {
namespace {

Eigen::Vector2d required_parameter(const SceneReader& reader, const JsonValue& value,
                                   const std::string& path, const char* key) {
  return reader.parameter(reader.require(value, path, key, "a material parameter [u, v]"),
                          join_json_path(path, key));
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

}  // namespace

// point_target ----------------------------------------------------------------------------------

std::unique_ptr<SceneConstraintSpec> ScenePointTargetConstraint::clone() const {
  return std::make_unique<ScenePointTargetConstraint>(*this);
}

void ScenePointTargetConstraint::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model", model},
          {"at", parameter_json(at)},
          {"target", schedule_json(target)}};
}

void ScenePointTargetConstraint::add(ConstraintSolver& solver, System& system,
                                     const BaumgarteParameters& parameters) const {
  solver.add(system, PointTargetConstraint(model, at, trajectory(target)), parameters);
}

bool ScenePointTargetConstraint::add_to_region(int index, SculptedRegion& region) const {
  if (model == index) {
    region.parameters.push_back(at);
  }
  return false;
}

std::unique_ptr<SceneConstraintSpec> read_point_target_constraint(const SceneReader& reader,
                                                                  const ModelNames& names,
                                                                  const JsonValue& constraint,
                                                                  const std::string& path) {
  reader.object(constraint, path, {"type", "model", "at", "target", "alpha", "beta"});
  auto spec = std::make_unique<ScenePointTargetConstraint>();
  spec->model = names.require(reader, constraint, path, "model");
  spec->at = required_parameter(reader, constraint, path, "at");
  spec->target = reader.vector_schedule(
      reader.require(constraint, path, "target", "[x, y, z] or keyframes"),
      join_json_path(path, "target"));
  return spec;
}

// point_to_point ---------------------------------------------------------------------------------

std::unique_ptr<SceneConstraintSpec> ScenePointToPointConstraint::clone() const {
  return std::make_unique<ScenePointToPointConstraint>(*this);
}

void ScenePointToPointConstraint::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model_a", model_a},
          {"at_a", parameter_json(at_a)},
          {"model_b", model_b},
          {"at_b", parameter_json(at_b)}};
}

void ScenePointToPointConstraint::add(ConstraintSolver& solver, System& system,
                                      const BaumgarteParameters& parameters) const {
  solver.add(system, PointToPointConstraint(model_a, at_a, model_b, at_b), parameters);
}

bool ScenePointToPointConstraint::add_to_region(int index, SculptedRegion& region) const {
  if (model_a == index) {
    region.parameters.push_back(at_a);
  }
  if (model_b == index) {
    region.parameters.push_back(at_b);
  }
  return false;
}

std::unique_ptr<SceneConstraintSpec> read_point_to_point_constraint(const SceneReader& reader,
                                                                    const ModelNames& names,
                                                                    const JsonValue& constraint,
                                                                    const std::string& path) {
  reader.object(constraint, path, {"type", "model_a", "at_a", "model_b", "at_b", "alpha", "beta"});
  auto spec = std::make_unique<ScenePointToPointConstraint>();
  spec->model_a = names.require(reader, constraint, path, "model_a");
  spec->at_a = required_parameter(reader, constraint, path, "at_a");
  spec->model_b = names.require(reader, constraint, path, "model_b");
  spec->at_b = required_parameter(reader, constraint, path, "at_b");
  return spec;
}

// hinge ------------------------------------------------------------------------------------------

std::unique_ptr<SceneConstraintSpec> SceneHingeConstraint::clone() const {
  return std::make_unique<SceneHingeConstraint>(*this);
}

void SceneHingeConstraint::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model_a", model_a},
          {"axis_a", {parameter_json(axis_a0), parameter_json(axis_a1)}},
          {"model_b", model_b},
          {"axis_b", {parameter_json(axis_b0), parameter_json(axis_b1)}}};
}

void SceneHingeConstraint::add(ConstraintSolver& solver, System& system,
                               const BaumgarteParameters& parameters) const {
  solver.add(system, HingeConstraint(model_a, axis_a0, axis_a1, model_b, axis_b0, axis_b1),
             parameters);
}

bool SceneHingeConstraint::add_to_region(int index, SculptedRegion& region) const {
  if (model_a == index) {
    region.parameters.insert(region.parameters.end(), {axis_a0, axis_a1});
  }
  if (model_b == index) {
    region.parameters.insert(region.parameters.end(), {axis_b0, axis_b1});
  }
  return false;
}

std::unique_ptr<SceneConstraintSpec> read_hinge_constraint(const SceneReader& reader,
                                                           const ModelNames& names,
                                                           const JsonValue& constraint,
                                                           const std::string& path) {
  reader.object(constraint, path,
                {"type", "model_a", "axis_a", "model_b", "axis_b", "alpha", "beta"});
  auto spec = std::make_unique<SceneHingeConstraint>();
  spec->model_a = names.require(reader, constraint, path, "model_a");
  read_axis(reader, constraint, path, "axis_a", spec->axis_a0, spec->axis_a1);
  spec->model_b = names.require(reader, constraint, path, "model_b");
  read_axis(reader, constraint, path, "axis_b", spec->axis_b0, spec->axis_b1);
  return spec;
}

// control_point ----------------------------------------------------------------------------------

std::unique_ptr<SceneConstraintSpec> SceneControlPointConstraint::clone() const {
  return std::make_unique<SceneControlPointConstraint>(*this);
}

void SceneControlPointConstraint::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model", model},
          {"control_point", control_point},
          {"target", json_array<3>(target)}};
}

void SceneControlPointConstraint::add(ConstraintSolver& solver, System& system,
                                      const BaumgarteParameters& parameters) const {
  solver.add(system, ControlPointConstraint(model, control_point, target), parameters);
}

bool SceneControlPointConstraint::add_to_region(int index, SculptedRegion& region) const {
  if (model == index) {
    region.control_points.push_back(control_point);
  }
  return false;
}

std::unique_ptr<SceneConstraintSpec> read_control_point_constraint(const SceneReader& reader,
                                                                   const ModelNames& names,
                                                                   const JsonValue& constraint,
                                                                   const std::string& path) {
  reader.object(constraint, path, {"type", "model", "control_point", "target", "alpha", "beta"});
  auto spec = std::make_unique<SceneControlPointConstraint>();
  spec->model = names.require(reader, constraint, path, "model");
  spec->control_point =
      reader.integer(reader.require(constraint, path, "control_point", "a control point index"),
                     join_json_path(path, "control_point"), 0, 1 << 30);
  spec->target = reader.point(reader.require(constraint, path, "target", "[x, y, z]"),
                              join_json_path(path, "target"));
  return spec;
}

// surface_normal ---------------------------------------------------------------------------------

std::unique_ptr<SceneConstraintSpec> SceneSurfaceNormalConstraint::clone() const {
  return std::make_unique<SceneSurfaceNormalConstraint>(*this);
}

void SceneSurfaceNormalConstraint::write(JsonOut& json) const {
  json = {{"type", type()},
          {"model", model},
          {"at", parameter_json(at)},
          {"direction", json_array<3>(direction)}};
}

void SceneSurfaceNormalConstraint::add(ConstraintSolver& solver, System& system,
                                       const BaumgarteParameters& parameters) const {
  solver.add(system, SurfaceNormalConstraint(model, at, direction), parameters);
}

bool SceneSurfaceNormalConstraint::add_to_region(int index, SculptedRegion& region) const {
  if (model == index) {
    region.parameters.push_back(at);
  }
  return false;
}

std::unique_ptr<SceneConstraintSpec> read_surface_normal_constraint(const SceneReader& reader,
                                                                    const ModelNames& names,
                                                                    const JsonValue& constraint,
                                                                    const std::string& path) {
  reader.object(constraint, path, {"type", "model", "at", "direction", "alpha", "beta"});
  auto spec = std::make_unique<SceneSurfaceNormalConstraint>();
  spec->model = names.require(reader, constraint, path, "model");
  spec->at = required_parameter(reader, constraint, path, "at");
  spec->direction = reader.point(reader.require(constraint, path, "direction", "[x, y, z]"),
                                 join_json_path(path, "direction"));
  if (!(spec->direction.norm() > 0.0)) {
    reader.fail(join_json_path(path, "direction"), "expected a non-zero direction");
  }
  return spec;
}

// curve_on_surface -------------------------------------------------------------------------------

std::unique_ptr<SceneConstraintSpec> SceneCurveOnSurfaceConstraint::clone() const {
  return std::make_unique<SceneCurveOnSurfaceConstraint>(*this);
}

void SceneCurveOnSurfaceConstraint::write(JsonOut& json) const {
  json = {{"type", type()},
          {"curve_model", curve_model},
          {"surface_model", surface_model},
          {"samples", samples}};
}

void SceneCurveOnSurfaceConstraint::add(ConstraintSolver& solver, System& system,
                                        const BaumgarteParameters& parameters) const {
  for (auto& constraint : curve_on_surface_constraints(system, curve_model, surface_model,
                                                       samples)) {
    solver.add(system, std::move(constraint), parameters);
  }
}

bool SceneCurveOnSurfaceConstraint::add_to_region(int index, SculptedRegion& /*region*/) const {
  return curve_model == index || surface_model == index;
}

std::unique_ptr<SceneConstraintSpec> read_curve_on_surface_constraint(const SceneReader& reader,
                                                                      const ModelNames& names,
                                                                      const JsonValue& constraint,
                                                                      const std::string& path) {
  reader.object(constraint, path,
                {"type", "curve_model", "surface_model", "samples", "alpha", "beta"});
  auto spec = std::make_unique<SceneCurveOnSurfaceConstraint>();
  spec->curve_model = names.require(reader, constraint, path, "curve_model");
  spec->surface_model = names.require(reader, constraint, path, "surface_model");
  reader.integer_key(constraint, path, "samples", spec->samples, 1, 10000);
  return spec;
}

}  // namespace dnurbs
