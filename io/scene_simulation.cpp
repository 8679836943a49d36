#include "dnurbs/io/scene_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dnurbs/core/memory_budget.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/core/sculpted_region.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_fit.h"
#include "dnurbs/io/scene_prescribed.h"

namespace dnurbs {
namespace {

// A material parameter of model `index`: in its domain (a D-NURBS model throws naming the value
// otherwise) and of its dimension (a curve takes [u]: a second parameter is an error).
void check_parameter(const System& system, const std::string& name, int index,
                     const Eigen::Vector2d& at) {
  const Model& model = system.model(index);
  if (model.parametric_dimension() == 1 && at.y() != 0.0) {
    throw make_error("model ", index, " (", name, ") is a curve: it takes one parameter [u], got [",
                     at.x(), ", ", at.y(), "]");
  }
  const Eigen::Vector3d x = system.position(index, at);
  if (!x.allFinite()) {
    throw make_error("the point of model ", index, " (", name, ") at [", at.x(), ", ", at.y(),
                     "] is not finite");
  }
}

std::string indexed(const char* list, size_t i) {
  return std::string(list) + '[' + std::to_string(i) + ']';
}

[[noreturn]] void fail(const Scene& scene, const std::string& path, const std::string& message) {
  std::string text = scene.source;
  text += ": ";
  text += path;
  text += ": ";
  text += message;
  throw Error(text);
}

// The model of a scene model: its type's model with the boundary conditions applied.
std::unique_ptr<Model> build_model(const SceneModel& spec) {
  std::unique_ptr<Model> model = spec.spec->build();
  if (spec.boundary.clamp_border) {
    model->fix_border();
  }
  for (const int i : spec.boundary.fixed_points) {
    model->fix_point(i);
  }
  return model;
}

// Local sculpting of model `index` (boundary.local_sculpting_margin >= 0): where its forces and
// constraints act; where one acts everywhere (gravity, pressure, ...), nothing is frozen.
void freeze_outside_scene_region(const Scene& scene, int index, Model& model) {
  SculptedRegion region;
  bool everywhere = false;
  for (const SceneForce& force : scene.forces) {
    everywhere = force.spec->add_to_region(index, region) || everywhere;
  }
  for (const SceneConstraint& constraint : scene.constraints) {
    everywhere = constraint.spec->add_to_region(index, region) || everywhere;
  }
  if (!everywhere) {
    model.freeze_outside(region,
                         scene.models[static_cast<size_t>(index)].boundary.local_sculpting_margin);
  }
}

// Mesh cells along one direction: resolution times the model's resolution_scale, at least
// `minimum` (SceneSimulation::mesh has checked the memory of the mesh, so the count fits an int).
int segments(int resolution, double scale, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(scale * resolution)));
}

}  // namespace

SceneSimulation::SceneSimulation(Scene scene) : scene_(std::move(scene)) {
  fit_initial_shapes(scene_);
  add_models();
  add_forces();
  add_constraints();
  try {
    contacts_ = SceneContacts(scene_, system_);  // penalty contact: one force per model
  } catch (const SceneKeyError& error) {
    fail(scene_, error.key(), error.what());
  }
  force_labels_.resize(static_cast<size_t>(system_.force_count()), "obstacles (penalty contact)");
  // Every material parameter of a force, constraint or probe is checked now, with its JSON path,
  // rather than at the first step
  const auto check = [&](const std::string& path, const auto& spec) {
    for (int m = 0; m < system_.model_count(); ++m) {
      SculptedRegion region;
      spec.add_to_region(m, region);
      for (const Eigen::Vector2d& at : region.parameters) {
        try {
          check_parameter(system_, scene_.models[static_cast<size_t>(m)].name, m, at);
        } catch (const Error& error) {
          fail(scene_, path, error.what());
        }
      }
    }
  };
  for (size_t i = 0; i < scene_.forces.size(); ++i) {
    check(indexed("forces", i) + ".at", *scene_.forces[i].spec);
  }
  for (size_t i = 0; i < scene_.constraints.size(); ++i) {
    check(indexed("constraints", i), *scene_.constraints[i].spec);
  }
  for (size_t i = 0; i < scene_.probes.size(); ++i) {
    const SceneProbe& probe = scene_.probes[i];
    try {
      check_parameter(system_, scene_.models[static_cast<size_t>(probe.model)].name, probe.model,
                      probe.at);
    } catch (const Error& error) {
      fail(scene_, indexed("probes", i) + ".at", error.what());
    }
  }
  IntegratorSettings settings;
  settings.scheme = parse_integrator_scheme(scene_.integrator.scheme);
  settings.newmark_beta = scene_.integrator.newmark_beta;
  settings.newmark_gamma = scene_.integrator.newmark_gamma;
  settings.newton_iterations = scene_.integrator.newton_iterations;
  settings.newton_tolerance = scene_.integrator.newton_tolerance;
  settings.automatic_newton = scene_.integrator.automatic_newton;
  settings.keep_factor_across_steps = scene_.integrator.keep_factor_across_steps;
  integrator_ = Integrator(settings);
  hash_ = scene_state_hash(scene_);
  budget_ = EnergyBudget({scene_.integrator.energy_growth, scene_.integrator.max_energy});
  // A non-finite energy (coordinates whose squares overflow) is the scene's fault: named now
  for (int i = 0; i < system_.model_count(); ++i) {
    const Model& model = system_.model(i);
    const Eigen::VectorXd q = system_.coordinates(i);
    const double energy =
        model.potential_energy(q) + model.kinetic_energy(q, system_.velocities(i));
    if (!std::isfinite(energy)) {
      fail(scene_, indexed("models", static_cast<size_t>(i)),
           "the initial energy of model '" + scene_.models[static_cast<size_t>(i)].name +
               "' is not finite (" + format_json_number(energy) +
               "): its coordinates (largest magnitude " +
               format_json_number(q.cwiseAbs().maxCoeff()) +
               ") are too large for its energy to be computed; scale the shape down");
    }
  }
  controls_ = SceneControls(scene_, system_);
  controls_.begin_frame(system_, 0);
  budget_.start(system_);
}

void SceneSimulation::add_models() {
  for (size_t i = 0; i < scene_.models.size(); ++i) {
    const SceneModel& spec = scene_.models[i];
    std::unique_ptr<Model> model;
    try {
      const auto [bytes, key] = spec.spec->memory_estimate();
      if (bytes > 0.0) {
        check_memory_budget(bytes, "the model", "models[" + std::to_string(i) + "]." + key);
      }
      model = build_model(spec);
    } catch (const Error& error) {
      fail(scene_, indexed("models", i), error.what());
    }
    if (spec.boundary.local_sculpting_margin >= 0) {
      try {
        freeze_outside_scene_region(scene_, static_cast<int>(i), *model);
      } catch (const Error& error) {
        fail(scene_, indexed("models", i) + ".boundary.local_sculpting_margin", error.what());
      }
    }
    const int index = system_.add_model(*model);
    try {
      spec.spec->add_model_forces(system_, index);
    } catch (const Error& error) {
      fail(scene_, indexed("models", i), error.what());
    }
    force_labels_.resize(static_cast<size_t>(system_.force_count()),
                         indexed("models", i) + " (" + spec.spec->type() + ")");
    // Curves are meshed as tubes of one radius for the whole run (frames do not flicker)
    tube_radii_.push_back(model->parametric_dimension() == 1
                              ? curve_tube_radius(*model, model->initial_coordinates())
                              : 0.0);
  }
}

void SceneSimulation::add_forces() {
  for (size_t i = 0; i < scene_.forces.size(); ++i) {
    const SceneForce& force = scene_.forces[i];
    try {
      force.spec->apply(system_, force.start, force.end);
      const std::string label = indexed("forces", i) + " (" + force.spec->type() + ")";
      force_labels_.resize(static_cast<size_t>(system_.force_count()), label);
      spring_labels_.resize(static_cast<size_t>(system_.spring_id_count()), label);
    } catch (const SceneKeyError& error) {
      fail(scene_, indexed("forces", i) + error.key(), error.what());
    } catch (const Error& error) {
      fail(scene_, indexed("forces", i), error.what());
    }
  }
}

void SceneSimulation::add_constraints() {
  for (size_t i = 0; i < scene_.constraints.size(); ++i) {
    const SceneConstraint& constraint = scene_.constraints[i];
    BaumgarteParameters parameters;
    parameters.alpha = constraint.alpha;
    parameters.beta = constraint.beta;
    try {
      constraint.spec->add(solver_, system_, parameters);
    } catch (const Error& error) {
      fail(scene_, indexed("constraints", i), error.what());
    }
  }
}

void SceneSimulation::step() {
  const Eigen::VectorXd q = system_.coordinates();
  const Eigen::VectorXd qd = system_.velocities();
  const bool valid = system_.accelerations_valid();
  const Eigen::VectorXd a = valid ? system_.accelerations() : Eigen::VectorXd();
  const double time = system_.time();
  const Eigen::VectorXd rest = system_.flowing_rest_coordinates();  // plastic rest shapes
  auto restore_last = [&]() {
    system_.set_state(q, qd, time);
    if (valid) {
      system_.set_accelerations(a);
    }
    system_.restore_flowing_rest_coordinates(rest);
  };
  const double dt = scene_.integrator.dt;
  if (prescribe_scene_coordinates(scene_.models, system_, time + dt)) {
    budget_.start(system_);  // keyed coordinates moved (io/scene_prescribed.h): the state jumped
  }
  try {
    if (controls_.all_held(steps_)) {
      system_.set_time(time + dt);  // nothing is computed before the start frames
    } else if (solver_.constraint_count() > 0) {
      solver_.step(integrator_, system_, dt);
    } else {
      integrator_.step(system_, dt);
    }
    contacts_.project(system_);  // projection contact, part of the step (checkpoints see it)
    controls_.hold(system_, steps_);
  } catch (const Error& error) {
    restore_last();
    throw SimulationDiverged(
        make_error("step ", steps_ + 1, " (t = ", time + dt, ") diverged: ", error.what()).what());
  }
  const EnergyCheck check = budget_.after_step(
      system_, solver_.constraint_count() > 0 ? solver_.constraint_force() : Eigen::VectorXd());
  if (!check.passed) {
    restore_last();
    std::ostringstream text;
    text << "step " << steps_ + 1 << " (t = " << time + dt << ") diverged: the energy "
         << check.energy;
    if (check.not_finite) {
      text << " is not finite";
    } else if (check.above_ceiling) {
      text << " exceeds integrator.max_energy = " << scene_.integrator.max_energy
           << " times the energy moved, " << std::max(1.0, check.scale);
    } else {
      text << " exceeds its budget " << check.budget << " (initial energy "
           << budget_.initial_energy() << " plus the work of the forces) by more than "
           << "integrator.energy_growth = " << scene_.integrator.energy_growth
           << " times the energy moved, " << check.scale;
    }
    text << "; driven by " << energy_driver(check) << ". The state is back at step " << steps_
         << " (t = " << time << ", energy " << budget_.energy() << ", which passed the check)";
    throw SimulationDiverged(text.str());
  }
  ++steps_;
  if (controls_.begin_frame(system_, steps_)) {
    budget_.start(system_);  // a reset or a new material: the energy jumps without work
  }
}

std::string SceneSimulation::energy_driver(const EnergyCheck& check) const {
  std::ostringstream text;
  const auto named = [&](const std::string& label) {
    text << label << ", with work " << check.driver_work << " in the step of growth "
         << check.growth;
  };
  switch (check.driver) {
    case EnergyDriver::kForce:
      named(force_labels_.at(static_cast<size_t>(check.index)));
      break;
    case EnergyDriver::kSpring:
      named(spring_labels_.at(static_cast<size_t>(check.index)));
      break;
    case EnergyDriver::kExtra:
      text << "the constraint forces (work " << check.driver_work << " in the step of growth "
           << check.growth << ")";
      break;
    default:
      text << divergence_setting(integrator_.settings(), system_, scene_.integrator.dt);
  }
  return text.str();
}

SceneSample SceneSimulation::sample() const {
  SceneSample s;
  s.step = steps_;
  s.time = system_.time();
  // The energy budget holds both at the current state (it checked it, or started from it)
  s.kinetic_energy = budget_.kinetic_energy();
  s.potential_energy = budget_.potential_energy();
  s.violations = solver_.violations(system_);
  for (const auto& probe : scene_.probes) {
    s.probes.push_back(system_.position(probe.model, probe.at));
  }
  return s;
}

std::vector<std::string> SceneSimulation::log_columns() const {
  std::vector<std::string> columns = {"time", "kinetic_energy", "potential_energy", "total_energy",
                                      "max_violation"};
  for (int i = 0; i < solver_.constraint_count(); ++i) {
    columns.push_back("violation_" + std::to_string(i));
  }
  for (const auto& probe : scene_.probes) {
    for (const char* axis : {"_x", "_y", "_z"}) {
      columns.push_back(probe.name + axis);
    }
  }
  return columns;
}

std::vector<double> SceneSimulation::log_row(const SceneSample& s) const {
  std::vector<double> row = {s.time, s.kinetic_energy, s.potential_energy,
                             s.kinetic_energy + s.potential_energy,
                             s.violations.size() > 0 ? s.violations.maxCoeff() : 0.0};
  for (Eigen::Index i = 0; i < s.violations.size(); ++i) {
    row.push_back(s.violations(i));
  }
  for (const auto& x : s.probes) {
    row.insert(row.end(), {x.x(), x.y(), x.z()});
  }
  return row;
}

std::vector<TriangleMesh> SceneSimulation::meshes(int resolution) const {
  std::vector<TriangleMesh> result;
  result.reserve(static_cast<size_t>(system_.model_count()));
  for (int i = 0; i < system_.model_count(); ++i) {
    result.push_back(mesh(i, resolution));
  }
  return result;
}

TriangleMesh SceneSimulation::mesh(int i, int resolution) const {
  const SceneModel& spec = scene_.models.at(static_cast<size_t>(i));
  const Model& model = system_.model(i);
  const Eigen::VectorXd q = system_.coordinates(i);
  const Eigen::Vector2d& scale = spec.resolution_scale;
  const std::string keys =
      "output.resolution (or --resolution) or models[" + std::to_string(i) + "].resolution_scale";
  const std::string what = scene_.source + ": the mesh of models[" + std::to_string(i) + "] (" +
                           spec.name + ") at resolution " + std::to_string(resolution) +
                           " x resolution_scale [" + format_json_number(scale.x()) + ", " +
                           format_json_number(scale.y()) + "]";
  ModelTessellationSettings settings;
  const bool curve = model.parametric_dimension() == 1;
  // Cells in double first: a scale of 1e9 must not overflow an int into a tiny mesh
  const double cells_u = std::round(scale.x() * resolution * (curve ? 4.0 : 1.0));
  const double cells_v = curve ? 12.0 : std::round(scale.y() * resolution);
  check_memory_budget(
      triangle_mesh_bytes((cells_u + 1.0) * (cells_v + 1.0), 2.0 * cells_u * cells_v), what, keys);
  if (curve) {
    // Curves: four times the surface resolution along the curve, a tube of 12 sides
    settings.segments_u = segments(4 * resolution, scale.x(), 3);
    settings.tube_radius = tube_radii_[static_cast<size_t>(i)];
    settings.tube_sides = 12;
  } else {
    const ParameterDomain domain = model.parameter_domain(q);
    settings.segments_u = segments(resolution, scale.x(), minimum_segments(domain, false));
    settings.segments_v = segments(resolution, scale.y(), minimum_segments(domain, true));
  }
  return tessellate_model(model, q, settings, spec.name);
}

void SceneSimulation::set_coordinates(const Eigen::VectorXd& q) {
  set_state(q, Eigen::VectorXd::Zero(system_.velocity_count()));
}

void SceneSimulation::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  system_.set_state(q, qd, system_.time());
  budget_.start(system_);
}

void SceneSimulation::continue_from(const SceneSimulation& previous) {
  const System& old = previous.system();
  if (old.coordinate_count() != system_.coordinate_count() ||
      old.velocity_count() != system_.velocity_count()) {
    throw make_error(scene_.source, ": cannot continue from a simulation of ",
                     old.coordinate_count(), " coordinates and ", old.velocity_count(),
                     " velocities; this one has ", system_.coordinate_count(), " and ",
                     system_.velocity_count());
  }
  controls_.restore(system_, previous.steps_done());  // before the acceleration, which it clears
  system_.set_state(old.coordinates(), old.velocities(), old.time());
  if (old.accelerations_valid()) {
    // Newmark continues from the last step's acceleration (with the constraint forces in it);
    // recomputing it here would leave the constraints out
    system_.set_accelerations(old.accelerations());
  }
  steps_ = previous.steps_done();
  budget_.start(system_);
}

int SceneSimulation::add_interactive_spring(int model, Spring spring, std::string label) {
  const int id = system_.add_spring(model, std::move(spring));
  spring_labels_.resize(static_cast<size_t>(system_.spring_id_count()));
  spring_labels_[static_cast<size_t>(id)] = std::move(label);
  return id;
}

void SceneSimulation::set_interactive_spring(int id, Spring spring) {
  system_.set_spring(id, std::move(spring));
}

void SceneSimulation::remove_interactive_spring(int id) {
  system_.remove_spring(id);
}

int SceneSimulation::add_interactive_force(int model, Force force, std::string label) {
  const int index = system_.add_force(model, std::move(force));
  force_labels_.resize(static_cast<size_t>(system_.force_count()));
  force_labels_[static_cast<size_t>(index)] = std::move(label);
  return index;
}

std::optional<Shape> SceneSimulation::shape(int i) const {
  return system_.model(i).exact_shape(system_.coordinates(i));
}

Checkpoint SceneSimulation::checkpoint() const {
  Checkpoint c;
  c.scene = scene_.source;
  c.scene_hash = hash_;
  c.step = steps_;
  c.time = system_.time();
  c.coordinates = system_.coordinates();
  c.velocities = system_.velocities();
  c.accelerations_valid = system_.accelerations_valid();
  if (c.accelerations_valid) {
    c.accelerations = system_.accelerations();
  }
  c.rest_coordinates = system_.flowing_rest_coordinates();
  return c;
}

void SceneSimulation::restore(const Checkpoint& checkpoint, const std::string& source) {
  if (checkpoint.scene_hash != hash_) {
    throw make_error(source, ": scene_hash: expected ", hash_, " (the hash of ", scene_.source,
                     "), got ", checkpoint.scene_hash,
                     ": the checkpoint belongs to another scene or the scene has changed");
  }
  // The step and time must be those of this run, or the resumed state would not be the run's
  if (checkpoint.step > scene_.step_count()) {
    throw make_error(source, ": step: expected a step of this run (0..", scene_.step_count(),
                     "), got ", checkpoint.step);
  }
  const double expected_time = checkpoint.step * scene_.integrator.dt;
  // The run's time is a sum of `step` dt's: rounding of at most step ulps of the time
  if (!(std::abs(checkpoint.time - expected_time) <= 4.0 * std::numeric_limits<double>::epsilon() *
                                                         (checkpoint.step + 1) *
                                                         std::max(1.0, std::abs(expected_time)))) {
    throw make_error(source, ": time: expected step * dt = ", checkpoint.step, " * ",
                     scene_.integrator.dt, " = ", expected_time, ", got ", checkpoint.time);
  }
  if (checkpoint.coordinates.size() != system_.coordinate_count()) {
    throw make_error(source, ": q: expected ", system_.coordinate_count(), " coordinates, got ",
                     checkpoint.coordinates.size());
  }
  if (checkpoint.velocities.size() != system_.velocity_count()) {
    throw make_error(source, ": qd: expected ", system_.velocity_count(), " velocities, got ",
                     checkpoint.velocities.size());
  }
  try {
    system_.restore_flowing_rest_coordinates(checkpoint.rest_coordinates);
  } catch (const Error& error) {
    throw make_error(source, ": rest: ", error.what());
  }
  controls_.restore(system_, checkpoint.step);  // before the acceleration, which it clears
  system_.set_state(checkpoint.coordinates, checkpoint.velocities, checkpoint.time);
  if (checkpoint.accelerations_valid) {
    system_.set_accelerations(checkpoint.accelerations);
  }
  steps_ = checkpoint.step;
  budget_.start(system_);
}

std::vector<SceneModelCost> SceneSimulation::cost() const {
  std::vector<SceneModelCost> costs;
  for (int i = 0; i < system_.model_count(); ++i) {
    const SceneModel& spec = scene_.models[static_cast<size_t>(i)];
    SceneModelCost c = model_cost(system_.model(i));
    c.name = spec.name;
    c.type = scene_model_type(spec);
    if (auto naive = spec.spec->naive_variant()) {
      SceneModel naive_model = spec;
      naive_model.spec = std::move(naive->first);
      const SceneModelCost naive_cost = model_cost(*build_model(naive_model));
      c.automatic_choice = naive->second;
      c.naive_active = naive_cost.velocities - naive_cost.fixed;
      c.naive_constant_matrices = naive_cost.constant_matrices;
      c.naive_solve_work = naive_cost.solve_work;
    }
    costs.push_back(c);
  }
  return costs;
}

}  // namespace dnurbs
