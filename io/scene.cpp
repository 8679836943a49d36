#include "dnurbs/io/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

#include "dnurbs/core/content_hash.h"
#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/animated_gltf.h"
#include "dnurbs/io/cad_file.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_registry.h"
#include "dnurbs/io/scene_writer.h"

namespace dnurbs {
namespace {

// "a, b and c": the model types whose table entry has `flag` set.
std::string types_with(bool SceneModelType::*flag) {
  std::vector<std::string> names;
  for (const SceneModelType& type : scene_model_types()) {
    if (type.*flag) {
      names.emplace_back(type.name);
    }
  }
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) {
    list += i == 0 ? "" : i + 1 == names.size() ? " and " : ", ";
    list += names[i];
  }
  return list;
}

void read_boundary(const SceneReader& reader, const JsonValue& value, const std::string& path,
                   const SceneModelType& type, SceneBoundary& result) {
  const std::string boundary_path = join_json_path(path, "boundary");
  reader.object(value, boundary_path, {"clamp_border", "fixed_points", "local_sculpting_margin"});
  const std::string name = type.name;
  reader.boolean_key(value, boundary_path, "clamp_border", result.clamp_border);
  if (result.clamp_border && !type.border) {
    reader.fail(join_json_path(boundary_path, "clamp_border"),
                "expected false: only " + types_with(&SceneModelType::border) +
                    " models have a border to clamp (this is a " + name + ")");
  }
  if (const JsonValue* fixed = reader.find(value, "fixed_points")) {
    result.fixed_points = reader.indices(*fixed, join_json_path(boundary_path, "fixed_points"));
    if (!type.points && !result.fixed_points.empty()) {
      reader.fail(join_json_path(boundary_path, "fixed_points"),
                  "expected no fixed points: a " + name + " has no control points or nodes");
    }
  }
  if (reader.find(value, "local_sculpting_margin") != nullptr) {
    if (!type.local_sculpting) {
      reader.fail(join_json_path(boundary_path, "local_sculpting_margin"),
                  "expected no local sculpting: only D-NURBS models have control points to "
                  "freeze (this is a " +
                      name + ")");
    }
    reader.integer_key(value, boundary_path, "local_sculpting_margin",
                       result.local_sculpting_margin, 0, 1000000);
  }
}

SceneModel read_model(const SceneReader& reader, const JsonValue& value, const std::string& path,
                      size_t index) {
  if (!value.is_object()) {
    reader.fail(path, "expected a model object, got " + describe_json_value(value));
  }
  const std::vector<SceneModelType>& types = scene_model_types();
  const SceneModelType& type =
      find_type(types, reader.choice(reader.require(value, path, "type", "a model type"),
                                     join_json_path(path, "type"), type_names(types)));
  SceneModel model;
  model.name = "model" + std::to_string(index);
  if (const JsonValue* name = reader.find(value, "name")) {
    model.name = reader.name(*name, join_json_path(path, "name"));
  }
  model.spec = type.read(reader, value, path);
  if (const JsonValue* boundary = reader.find(value, "boundary")) {
    read_boundary(reader, *boundary, path, type, model.boundary);
  }
  if (const JsonValue* scale = reader.find(value, "resolution_scale")) {
    model.resolution_scale =
        reader.vector<2>(*scale, join_json_path(path, "resolution_scale"), "[scale_u, scale_v]");
    if (!(model.resolution_scale.array() > 0.0).all()) {
      reader.fail(join_json_path(path, "resolution_scale"), "expected [scale_u, scale_v] > 0");
    }
  }
  return model;
}

SceneForce read_force(const SceneReader& reader, const ModelNames& names, const JsonValue& value,
                      const std::string& path) {
  if (!value.is_object()) {
    reader.fail(path, "expected a force object, got " + describe_json_value(value));
  }
  const std::vector<SceneForceType>& types = scene_force_types();
  const SceneForceType& type =
      find_type(types, reader.choice(reader.require(value, path, "type", "a force type"),
                                     join_json_path(path, "type"), type_names(types)));
  SceneForce force;
  force.spec = type.read(reader, names, value, path);
  reader.number_key(value, path, "start", force.start);
  if (const JsonValue* end = reader.find(value, "end")) {
    force.end = reader.number(*end, join_json_path(path, "end"));
    if (!(force.end > force.start)) {
      reader.fail(join_json_path(path, "end"), "expected an end time > start (" +
                                                   format_json_number(force.start) + "), got " +
                                                   format_json_number(force.end));
    }
  }
  return force;
}

SceneConstraint read_constraint(const SceneReader& reader, const ModelNames& names,
                                const JsonValue& value, const std::string& path) {
  if (!value.is_object()) {
    reader.fail(path, "expected a constraint object, got " + describe_json_value(value));
  }
  const std::vector<SceneConstraintType>& types = scene_constraint_types();
  const SceneConstraintType& type =
      find_type(types, reader.choice(reader.require(value, path, "type", "a constraint type"),
                                     join_json_path(path, "type"), type_names(types)));
  SceneConstraint constraint;
  constraint.spec = type.read(reader, names, value, path);
  reader.number_key(value, path, "alpha", constraint.alpha, 0.0, false);
  reader.number_key(value, path, "beta", constraint.beta, 0.0, false);
  return constraint;
}

void read_models(const SceneReader& reader, const JsonValue& root, Scene& scene) {
  const JsonValue& models =
      reader.array(reader.require(root, "", "models", "an array of models"), "models", "models");
  if (models.empty()) {
    reader.fail("models", "expected at least one model, got an empty array");
  }
  for (size_t i = 0; i < models.size(); ++i) {
    scene.models.push_back(read_model(reader, models[i], json_index_path("models", i), i));
    for (size_t j = 0; j < i; ++j) {
      if (scene.models[j].name == scene.models[i].name) {
        reader.fail(json_index_path("models", i) + ".name",
                    "expected a unique model name, got \"" + scene.models[i].name +
                        "\" again (models[" + std::to_string(j) + "])");
      }
    }
  }
}

void read_integrator(const SceneReader& reader, const JsonValue& integrator,
                     SceneIntegrator& result) {
  const std::string path = "integrator";
  reader.object(
      integrator, path,
      {"scheme", "dt", "newton_iterations", "newton_tolerance", "automatic_newton",
       "keep_factor_across_steps", "newmark_beta", "newmark_gamma", "max_energy", "energy_growth"});
  if (const JsonValue* scheme = reader.find(integrator, "scheme")) {
    result.scheme =
        reader.choice(*scheme, "integrator.scheme", {"central", "implicit-euler", "newmark"});
  }
  reader.number_key(integrator, path, "dt", result.dt, 0.0, true);
  reader.integer_key(integrator, path, "newton_iterations", result.newton_iterations, 0, 1000);
  reader.number_key(integrator, path, "newton_tolerance", result.newton_tolerance, 0.0, false);
  reader.boolean_key(integrator, path, "automatic_newton", result.automatic_newton);
  reader.boolean_key(integrator, path, "keep_factor_across_steps", result.keep_factor_across_steps);
  reader.number_key(integrator, path, "newmark_beta", result.newmark_beta, 0.0, true);
  reader.number_key(integrator, path, "newmark_gamma", result.newmark_gamma, 0.0, true);
  reader.number_key(integrator, path, "max_energy", result.max_energy, 0.0, true);
  reader.number_key(integrator, path, "energy_growth", result.energy_growth, 0.0, false);
}

void read_run(const SceneReader& reader, const JsonValue& root, Scene& scene) {
  const JsonValue& run = reader.require(root, "", "run", "{\"steps\": N} or {\"duration\": T}");
  reader.object(run, "run", {"steps", "duration", "frames", "frame_rate", "substeps"});
  const JsonValue* steps = reader.find(run, "steps");
  const JsonValue* duration = reader.find(run, "duration");
  const JsonValue* frames = reader.find(run, "frames");
  if (frames != nullptr && (steps != nullptr || duration != nullptr)) {
    reader.fail("run.frames", "expected \"frames\" without \"steps\" or \"duration\"");
  }
  if (frames == nullptr && (steps == nullptr) == (duration == nullptr)) {
    reader.fail("run", "expected exactly one of \"steps\" and \"duration\" (or \"frames\")");
  }
  if (frames == nullptr) {
    for (const char* key : {"frame_rate", "substeps"}) {
      if (reader.find(run, key) != nullptr) {
        reader.fail(join_json_path("run", key), "expected only with \"frames\"");
      }
    }
  } else {
    // Sub-stepping to a frame rate (Romero 2005, section 4.3): N steps of 1 / (R N) per frame
    scene.frames = reader.integer(*frames, "run.frames", 1, 100000000);
    scene.frame_rate =
        reader.bounded(reader.require(run, "run", "frame_rate", "frames per unit time > 0"),
                       "run.frame_rate", 0.0, true);
    scene.substeps = 1;
    reader.integer_key(run, "run", "substeps", scene.substeps, 1, 100000);
    if (const JsonValue* integrator = reader.find(root, "integrator");
        integrator != nullptr && reader.find(*integrator, "dt") != nullptr) {
      reader.fail("integrator.dt",
                  "expected no dt with run.frames (it is 1 / (frame_rate substeps))");
    }
    if (static_cast<double>(scene.frames) * scene.substeps > 1e8) {
      reader.fail("run.frames", "expected at most 1e8 steps (frames times substeps)");
    }
    scene.steps = scene.frames * scene.substeps;
    scene.integrator.dt = 1.0 / (scene.frame_rate * scene.substeps);
    scene.output.log_every = scene.substeps;
    scene.output.mesh_every = scene.substeps;
    return;
  }
  if (steps != nullptr) {
    scene.steps = reader.integer(*steps, "run.steps", 1, 100000000);
  } else {
    scene.duration = reader.bounded(*duration, "run.duration", 0.0, true);
    if (scene.duration / scene.integrator.dt > 1e8) {
      reader.fail("run.duration", "expected at most 1e8 steps of integrator.dt, got " +
                                      format_json_number(scene.duration / scene.integrator.dt));
    }
  }
}

void read_probes(const SceneReader& reader, const ModelNames& names, const JsonValue& probes,
                 std::vector<SceneProbe>& result) {
  reader.array(probes, "probes", "probes");
  for (size_t i = 0; i < probes.size(); ++i) {
    const std::string path = json_index_path("probes", i);
    const JsonValue& probe = probes[i];
    reader.object(probe, path, {"name", "model", "at"});
    SceneProbe p;
    p.name = "probe" + std::to_string(i);
    if (const JsonValue* name = reader.find(probe, "name")) {
      p.name = reader.name(*name, join_json_path(path, "name"));  // names CSV columns
    }
    p.model = names.require(reader, probe, path, "model");
    p.at = reader.parameter(reader.require(probe, path, "at", "a material parameter [u, v]"),
                            join_json_path(path, "at"));
    result.push_back(p);
  }
}

void read_output(const SceneReader& reader, const JsonValue& output, SceneOutput& o) {
  const std::string path = "output";
  reader.object(output, path,
                {"mesh_every", "format", "resolution", "final_mesh", "preview", "log_every",
                 "checkpoint_every", "name", "shape_files", "up_axis", "animation", "cad_format"});
  reader.integer_key(output, path, "mesh_every", o.mesh_every, 0, 100000000);
  if (const JsonValue* format = reader.find(output, "format")) {
    const std::initializer_list<const char*> formats = {"obj", "stl", "ply", "gltf", "glb"};
    if (format->is_array()) {
      if (format->empty()) {
        reader.fail("output.format", "expected a format or a non-empty array of formats, got " +
                                         describe_json_value(*format));
      }
      o.formats.clear();
      for (size_t i = 0; i < format->size(); ++i) {
        const std::string at = json_index_path("output.format", i);
        std::string one = reader.choice((*format)[i], at, formats);
        if (std::find(o.formats.begin(), o.formats.end(), one) != o.formats.end()) {
          reader.fail(at, "format \"" + one + "\" listed twice");
        }
        o.formats.push_back(std::move(one));
      }
    } else {
      o.formats = {reader.choice(*format, "output.format", formats)};
    }
  }
  if (const JsonValue* up = reader.find(output, "up_axis")) {
    o.up_axis = reader.choice(*up, "output.up_axis", {"z", "y"});
  }
  reader.integer_key(output, path, "resolution", o.resolution, 3, 1024);
  reader.boolean_key(output, path, "final_mesh", o.final_mesh);
  reader.boolean_key(output, path, "preview", o.preview);
  reader.boolean_key(output, path, "shape_files", o.shape_files);
  reader.boolean_key(output, path, "animation", o.animation);
  if (const JsonValue* cad = reader.find(output, "cad_format")) {
    o.cad_format = reader.choice(*cad, "output.cad_format", {"step", "iges", "obj"});
    if (o.cad_format != "obj" && !cad_exchange_available()) {
      reader.fail("output.cad_format", "\"" + o.cad_format +
                                           "\" needs dnurbs built with Open CASCADE "
                                           "(libocct-data-exchange-dev); \"obj\" needs nothing");
    }
  }
  if (o.animation && o.mesh_every == 0) {
    reader.fail("output.animation",
                "expected false when output.mesh_every is 0 (the animation "
                "is made of the frames)");
  }
  reader.integer_key(output, path, "log_every", o.log_every, 1, 100000000);
  reader.integer_key(output, path, "checkpoint_every", o.checkpoint_every, 0, 100000000);
  if (const JsonValue* name = reader.find(output, "name")) {
    o.name = reader.name(*name, "output.name");
  }
  if (o.preview && !o.final_mesh) {
    reader.fail("output.preview", "expected false when output.final_mesh is false");
  }
}

void read_design(const SceneReader& reader, const JsonValue& design, SceneDesign& d) {
  const std::string path = "design";
  reader.object(design, path,
                {"algorithm", "variable_tolerance", "energy_tolerance", "constraint_tolerance",
                 "max_evaluations", "max_seconds"});
  if (const JsonValue* algorithm = reader.find(design, "algorithm")) {
    d.algorithm = reader.choice(*algorithm, "design.algorithm", {"slsqp", "auglag_lbfgs"});
  }
  reader.number_key(design, path, "variable_tolerance", d.variable_tolerance, 0.0, false);
  reader.number_key(design, path, "energy_tolerance", d.energy_tolerance, 0.0, false);
  reader.number_key(design, path, "constraint_tolerance", d.constraint_tolerance, 0.0, false);
  reader.integer_key(design, path, "max_evaluations", d.max_evaluations, 1, 100000000);
  reader.number_key(design, path, "max_seconds", d.max_seconds, 0.0, false);
}

Scene read_scene(const SceneReader& reader, const JsonValue& root) {
  reader.object(root, "",
                {"description", "models", "forces", "constraints", "integrator", "run", "probes",
                 "output", "design", "obstacles", "contact"});
  Scene scene;
  scene.source = reader.source();
  scene.directory = reader.directory();
  if (const JsonValue* description = reader.find(root, "description")) {
    scene.description = reader.string(*description, "description");
  }
  read_models(reader, root, scene);
  std::vector<std::string> model_names;
  for (const SceneModel& model : scene.models) {
    model_names.push_back(model.name);
  }
  const ModelNames names(std::move(model_names));
  if (const JsonValue* forces = reader.find(root, "forces")) {
    reader.array(*forces, "forces", "forces");
    for (size_t i = 0; i < forces->size(); ++i) {
      scene.forces.push_back(read_force(reader, names, (*forces)[i], json_index_path("forces", i)));
    }
  }
  if (const JsonValue* constraints = reader.find(root, "constraints")) {
    reader.array(*constraints, "constraints", "constraints");
    for (size_t i = 0; i < constraints->size(); ++i) {
      scene.constraints.push_back(
          read_constraint(reader, names, (*constraints)[i], json_index_path("constraints", i)));
    }
  }
  read_scene_obstacles(reader, root, scene.obstacles, scene.contact);
  if (const JsonValue* integrator = reader.find(root, "integrator")) {
    read_integrator(reader, *integrator, scene.integrator);
  }
  read_run(reader, root, scene);
  if (const JsonValue* probes = reader.find(root, "probes")) {
    read_probes(reader, names, *probes, scene.probes);
  }
  if (const JsonValue* output = reader.find(root, "output")) {
    read_output(reader, *output, scene.output);
    const SceneOutput& o = scene.output;
    if (o.animation && scene.step_count() / o.mesh_every + 1 > kMaxAnimationFrames) {
      reader.fail("output.animation",
                  "the run has " + std::to_string(scene.step_count() / o.mesh_every + 1) +
                      " frames, more than an animation holds (" +
                      std::to_string(kMaxAnimationFrames) + "); raise output.mesh_every");
    }
  }
  if (const JsonValue* design = reader.find(root, "design")) {
    read_design(reader, *design, scene.design.emplace());
  }
  scene.input_digests = reader.input_digests();
  return scene;
}

// Writer ----------------------------------------------------------------------------------------

JsonOut model_json(const SceneModel& model) {
  JsonOut json;
  json["name"] = model.name;
  json["type"] = scene_model_type(model);
  model.spec->write(json);
  const SceneBoundary& boundary = model.boundary;
  if (boundary.clamp_border || !boundary.fixed_points.empty() ||
      boundary.local_sculpting_margin >= 0) {
    json["boundary"] = {{"clamp_border", boundary.clamp_border},
                        {"fixed_points", boundary.fixed_points}};
    if (boundary.local_sculpting_margin >= 0) {
      json["boundary"]["local_sculpting_margin"] = boundary.local_sculpting_margin;
    }
  }
  if (model.resolution_scale != Eigen::Vector2d::Ones()) {
    json["resolution_scale"] = parameter_json(model.resolution_scale);
  }
  return json;
}

JsonOut force_json(const SceneForce& force) {
  JsonOut json;
  force.spec->write(json);
  json["start"] = force.start;
  if (std::isfinite(force.end)) {
    json["end"] = force.end;
  }
  return json;
}

JsonOut constraint_json(const SceneConstraint& constraint) {
  JsonOut json;
  constraint.spec->write(json);
  json["alpha"] = constraint.alpha;
  if (constraint.beta >= 0.0) {
    json["beta"] = constraint.beta;
  }
  return json;
}

JsonOut scene_json(const Scene& scene, bool with_output) {
  JsonOut root;
  if (with_output && !scene.description.empty()) {
    root["description"] = scene.description;
  }
  root["models"] = JsonOut::array();
  for (const auto& model : scene.models) {
    root["models"].push_back(model_json(model));
  }
  root["forces"] = JsonOut::array();
  for (const auto& force : scene.forces) {
    root["forces"].push_back(force_json(force));
  }
  root["constraints"] = JsonOut::array();
  for (const auto& constraint : scene.constraints) {
    root["constraints"].push_back(constraint_json(constraint));
  }
  write_scene_obstacles(scene.obstacles, scene.contact, root);
  const SceneIntegrator& s = scene.integrator;
  root["integrator"] = {{"scheme", s.scheme},
                        {"dt", s.dt},
                        {"newton_iterations", s.newton_iterations},
                        {"newton_tolerance", s.newton_tolerance},
                        {"automatic_newton", s.automatic_newton},
                        {"keep_factor_across_steps", s.keep_factor_across_steps},
                        {"newmark_beta", s.newmark_beta},
                        {"newmark_gamma", s.newmark_gamma},
                        {"max_energy", s.max_energy},
                        {"energy_growth", s.energy_growth}};
  if (scene.frames > 0) {
    root["run"] = {
        {"frames", scene.frames}, {"frame_rate", scene.frame_rate}, {"substeps", scene.substeps}};
    root["integrator"].erase("dt");
  } else if (scene.steps > 0) {
    root["run"] = {{"steps", scene.steps}};
  } else {
    root["run"] = {{"duration", scene.duration}};
  }
  root["probes"] = JsonOut::array();
  for (const auto& probe : scene.probes) {
    root["probes"].push_back(
        {{"name", probe.name}, {"model", probe.model}, {"at", parameter_json(probe.at)}});
  }
  if (with_output) {
    const SceneOutput& o = scene.output;
    root["output"] = {
        {"mesh_every", o.mesh_every},
        {"format", o.formats.size() == 1 ? JsonOut(o.formats.front()) : JsonOut(o.formats)},
        {"resolution", o.resolution},
        {"final_mesh", o.final_mesh},
        {"preview", o.preview},
        {"log_every", o.log_every},
        {"checkpoint_every", o.checkpoint_every},
        {"name", o.name},
        {"shape_files", o.shape_files},
        {"up_axis", o.up_axis},
        {"animation", o.animation}};
    if (!o.cad_format.empty()) {
      root["output"]["cad_format"] = o.cad_format;
    }
  }
  if (scene.design) {
    const SceneDesign& d = *scene.design;
    root["design"] = {{"algorithm", d.algorithm},
                      {"variable_tolerance", d.variable_tolerance},
                      {"energy_tolerance", d.energy_tolerance},
                      {"constraint_tolerance", d.constraint_tolerance},
                      {"max_evaluations", d.max_evaluations},
                      {"max_seconds", d.max_seconds}};
  }
  return root;
}

}  // namespace

std::string scene_model_type(const SceneModel& model) {
  return model.spec->type();
}

int Scene::step_count() const {
  if (steps > 0) {
    return steps;
  }
  // duration / dt rounded up, with a margin for the rounding of an exact multiple
  return static_cast<int>(std::ceil(duration / integrator.dt - 1e-9));
}

bool operator==(const SceneModel& a, const SceneModel& b) {
  return model_json(a) == model_json(b);
}

bool operator==(const SceneForce& a, const SceneForce& b) {
  return force_json(a) == force_json(b);
}

bool operator==(const SceneConstraint& a, const SceneConstraint& b) {
  return constraint_json(a) == constraint_json(b);
}

bool operator==(const Scene& a, const Scene& b) {
  return scene_json(a, true) == scene_json(b, true);
}

Scene parse_scene_json(const std::string& text, const std::string& source,
                       const std::filesystem::path& directory) {
  const SceneReader reader(source, directory);
  return read_scene(reader, parse_json_document(text, source));
}

Scene read_scene_file(const std::filesystem::path& path) {
  return parse_scene_json(read_input_file(path, "scene file"), path.string(), path.parent_path());
}

std::string scene_to_json(const Scene& scene) {
  return scene_json(scene, true).dump(2) + "\n";
}

std::string scene_state_hash(const Scene& scene) {
  std::string text = scene_json(scene, false).dump();
  for (const std::string& digest : scene.input_digests) {
    text += '\n';
    text += digest;
  }
  return content_hash(text);
}

}  // namespace dnurbs
