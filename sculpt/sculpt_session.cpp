#include "dnurbs/sculpt/sculpt_session.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

#include "dnurbs/io/mesh_export.h"
#include "dnurbs/io/output_path.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/sculpt/sculpt_frame.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;

constexpr std::size_t kUndoDepth = 32;
// Scene values used when the scene has no D-NURBS model to read them from.
constexpr std::array<double, 6> kFallbackSettings = {100.0, 0.0, 0.0, 1.0, 0.0, 0.01};

std::string dump(const Json& json) {
  // Replace, not throw, on invalid UTF-8: an error message may quote a client's bytes
  return json.dump(-1, ' ', false, Json::error_handler_t::replace);
}

Json array3(const Eigen::Vector3d& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

std::string error_message(const std::string& message, const std::string& request,
                          std::optional<long long> id) {
  Json json = {{"type", "error"}, {"message", message}, {"request", request}};
  if (id) {
    json["id"] = *id;
  }
  return dump(json);
}

Json reply(const char* type, const SculptRequest& request) {
  Json json = {{"type", type}};
  if (request.id) {
    json["id"] = *request.id;
  }
  return json;
}

// The control points of a model's exact shape and the segments of its net (pairs of indices):
// the rows and columns of a surface's grid, the polygon of a curve. Empty for other models.
struct ControlNet {
  Eigen::MatrixX3d points;
  std::vector<int> lines;
};

ControlNet control_net(const SceneSimulation& simulation, int i) {
  ControlNet net;
  const std::optional<Shape> shape = simulation.shape(i);
  if (!shape) {
    return net;
  }
  if (const auto* curve = std::get_if<NurbsCurve>(&*shape)) {
    net.points = curve->control_points();
    for (int k = 0; k + 1 < curve->control_point_count(); ++k) {
      net.lines.insert(net.lines.end(), {k, k + 1});
    }
    return net;
  }
  const auto& surface = std::get<NurbsSurface>(*shape);
  net.points = surface.control_points();
  const int nu = surface.control_point_count_u();
  const int nv = surface.control_point_count_v();
  for (int a = 0; a < nu; ++a) {
    for (int b = 0; b < nv; ++b) {
      if (a + 1 < nu) {
        net.lines.insert(net.lines.end(), {surface.control_point_index(a, b),
                                           surface.control_point_index(a + 1, b)});
      }
      if (b + 1 < nv) {
        net.lines.insert(net.lines.end(), {surface.control_point_index(a, b),
                                           surface.control_point_index(a, b + 1)});
      }
    }
  }
  return net;
}

}  // namespace

SculptSession::SculptSession(Scene scene, SculptSessionOptions options)
    : scene_(std::move(scene)), options_(std::move(options)) {
  if (options_.resolution < 3 || options_.resolution > 256) {
    throw make_error("sculpt session: resolution ", options_.resolution, " is outside [3, 256]");
  }
  if (!(options_.messages_per_second > 0.0) || !std::isfinite(options_.messages_per_second)) {
    throw make_error("sculpt session: messages_per_second ", options_.messages_per_second,
                     " is not a positive finite number");
  }
  const SculptSettingRange& stiffness = sculpt_setting_range(SculptSetting::kStiffness);
  if (!(options_.stiffness > stiffness.min && options_.stiffness <= stiffness.max)) {
    throw make_error("sculpt session: stiffness ", options_.stiffness, " is outside (0, ",
                     stiffness.max, "]");
  }
  const SculptSettingOverrides values = sculpt_scene_settings(scene_);
  for (std::size_t k = 0; k < settings_.size(); ++k) {
    settings_[k] = values[k].value_or(kFallbackSettings[k]);
  }
  settings_[static_cast<std::size_t>(SculptSetting::kStiffness)] = options_.stiffness;
  adopt(build(overrides_, pins_, false));
  const System& system = simulation_->system();
  for (int i = 0; i < system.model_count(); ++i) {
    const Model& model = system.model(i);
    const ParameterDomain domain = model.parameter_domain(system.coordinates(i));
    limits_.models.push_back({model.parametric_dimension(),
                              Eigen::Vector2d(domain.u_min, domain.v_min),
                              Eigen::Vector2d(domain.u_max, domain.v_max)});
  }
  last_sent_.resize(static_cast<std::size_t>(system.model_count()));
}

SculptSession::~SculptSession() = default;

int SculptSession::connect() {
  const int id = next_client_++;
  Client client;
  client.tokens = options_.messages_per_second;
  client.last_refill = -1.0;
  clients_[id] = client;
  return id;
}

void SculptSession::disconnect(int client) {
  std::vector<int> owned;
  for (const auto& [id, drag] : drags_) {
    if (drag.client == client) {
      owned.push_back(id);
    }
  }
  for (const int id : owned) {
    end_drag(id);
  }
  clients_.erase(client);
}

bool SculptSession::take_token(Client& client, double now) const {
  if (client.last_refill >= 0.0) {
    client.tokens =
        std::min(options_.messages_per_second,
                 client.tokens + (now - client.last_refill) * options_.messages_per_second);
  }
  client.last_refill = now;
  if (client.tokens < 1.0) {
    return false;
  }
  client.tokens -= 1.0;
  return true;
}

SculptReply SculptSession::handle(int client, std::string_view text, double now) {
  SculptReply result;
  const auto found = clients_.find(client);
  if (found == clients_.end()) {
    result.messages.push_back(error_message("unknown client " + std::to_string(client), "", {}));
    return result;
  }
  if (!take_token(found->second, now)) {
    // One warning a second at most: a flood is not answered message for message
    if (now - found->second.last_flood_warning >= 1.0) {
      found->second.last_flood_warning = now;
      result.messages.push_back(
          error_message("too many messages: at most " +
                            std::to_string(static_cast<int>(options_.messages_per_second)) +
                            " a second; messages dropped",
                        "", {}));
    }
    return result;
  }
  std::optional<SculptRequest> request;
  try {
    request = parse_sculpt_request(text, limits_);
    apply(client, *request, result);
  } catch (const SculptRequestError& error) {
    result = {{error_message(error.what(), error.request(), error.id())}, false};
  } catch (const std::exception& error) {
    result = {{error_message(error.what(), request ? request->name : "",
                             request ? request->id : std::nullopt)},
              false};
  }
  return result;
}

void SculptSession::apply(int client, const SculptRequest& request, SculptReply& result) {
  switch (request.type) {
    case SculptRequestType::kGrab:
    case SculptRequestType::kPush: {
      Json json = reply("grabbed", request);
      json["drag"] = begin_drag(client, request);
      result.messages.push_back(dump(json));
      return;
    }
    case SculptRequestType::kMove:
      move_drag(client, request);
      return;
    case SculptRequestType::kRelease: {
      const auto drag = drags_.find(request.drag);
      if (drag == drags_.end() || drag->second.client != client) {
        throw make_error("release: no drag ", request.drag, " of this client");
      }
      end_drag(request.drag);
      Json json = reply("released", request);
      json["drag"] = request.drag;
      result.messages.push_back(dump(json));
      return;
    }
    case SculptRequestType::kPin: {
      const Eigen::Vector3d target = simulation_->system().position(request.model, *request.at);
      std::vector<SculptPin> pins = pins_;
      pins.push_back({request.model, *request.at, target});
      adopt(build(overrides_, pins, true));
      pins_ = std::move(pins);
      Json json = reply("pinned", request);
      json["pin"] = static_cast<int>(pins_.size()) - 1;
      json["position"] = array3(target);
      result.messages.push_back(dump(json));
      result.status_changed = true;
      return;
    }
    case SculptRequestType::kSet:
      change_setting(request.setting, request.value);
      result.status_changed = true;
      return;
    case SculptRequestType::kPlay:
      playing_ = true;
      diverged_.clear();
      result.status_changed = true;
      return;
    case SculptRequestType::kPause:
      playing_ = false;
      result.status_changed = true;
      return;
    case SculptRequestType::kStep:
      if (!playing_) {
        ++pending_steps_;
      }
      return;
    case SculptRequestType::kReset: {
      std::unique_ptr<SceneSimulation> fresh = build(overrides_, {}, false);
      drags_.clear();
      pins_.clear();
      undo_.clear();
      diverged_.clear();
      adopt(std::move(fresh));
      result.status_changed = true;
      return;
    }
    case SculptRequestType::kUndo:
      undo(client);
      result.status_changed = true;
      return;
    case SculptRequestType::kSave: {
      Json json = reply("saved", request);
      json["files"] = save();
      result.messages.push_back(dump(json));
      return;
    }
    case SculptRequestType::kQuery: {
      Json json = reply("point", request);
      json["position"] = array3(simulation_->system().position(request.model, *request.at));
      result.messages.push_back(dump(json));
      return;
    }
    case SculptRequestType::kShape: {
      const std::optional<Shape> shape = simulation_->shape(request.model);
      if (!shape) {
        throw make_error("shape: model ", request.model, " (",
                         scene_.models[static_cast<std::size_t>(request.model)].name,
                         ") has no exact shape (D-NURBS curves and surfaces have one)");
      }
      Json json = reply("shape", request);
      json["model"] = request.model;
      json["shape"] = Json::parse(shape_to_json(*shape));
      result.messages.push_back(dump(json));
      return;
    }
  }
}

Spring SculptSession::drag_spring(const Drag& drag) const {
  SpringState state{drag.at, drag.vector,
                    settings_[static_cast<std::size_t>(SculptSetting::kStiffness)]};
  return [state](double) { return state; };
}

int SculptSession::begin_drag(int client, const SculptRequest& request) {
  Drag drag;
  drag.client = client;
  drag.model = request.model;
  drag.push = request.type == SculptRequestType::kPush;
  drag.at = *request.at;
  drag.vector = drag.push ? *request.force : *request.target;
  const int id = next_drag_;
  if (!drag.push) {
    drag.spring = simulation_->add_interactive_spring(
        drag.model, drag_spring(drag),
        "the drag " + std::to_string(id) + " of client " + std::to_string(client) + " on " +
            scene_.models[static_cast<std::size_t>(drag.model)].name);
  }
  ++next_drag_;
  const System& system = simulation_->system();
  undo_.push_back({client, id, system.coordinates(), system.velocities()});
  if (undo_.size() > kUndoDepth) {
    undo_.erase(undo_.begin());
  }
  drags_[id] = drag;
  return id;
}

void SculptSession::move_drag(int client, const SculptRequest& request) {
  const auto found = drags_.find(request.drag);
  if (found == drags_.end() || found->second.client != client) {
    throw make_error("move: no drag ", request.drag, " of this client");
  }
  Drag moved = found->second;
  if (moved.push != request.force.has_value()) {
    throw make_error("move: drag ", request.drag, " is a ", moved.push ? "push" : "spring",
                     ": send \"", moved.push ? "force" : "target", "\"");
  }
  if (request.at) {
    const SculptRequestLimits::ModelLimits& model =
        limits_.models[static_cast<std::size_t>(moved.model)];
    const Eigen::Vector2d& u = *request.at;
    for (int k = 0; k < model.parametric_dimension; ++k) {
      if (u(k) < model.min(k) || u(k) > model.max(k)) {
        throw make_error("move: at[", k, "] = ", u(k), " is outside the domain [", model.min(k),
                         ", ", model.max(k), "] of model ", moved.model);
      }
    }
    moved.at = u;
  }
  moved.vector = moved.push ? *request.force : *request.target;
  if (!moved.push) {
    simulation_->set_interactive_spring(moved.spring, drag_spring(moved));
  }
  found->second = moved;
}

void SculptSession::end_drag(int id) {
  const auto found = drags_.find(id);
  if (found->second.spring >= 0) {
    simulation_->remove_interactive_spring(found->second.spring);
  }
  drags_.erase(found);
}

void SculptSession::change_setting(SculptSetting setting, double value) {
  const auto k = static_cast<std::size_t>(setting);
  if (setting == SculptSetting::kStiffness) {
    settings_[k] = value;
    for (const auto& [id, drag] : drags_) {
      if (!drag.push) {
        simulation_->set_interactive_spring(drag.spring, drag_spring(drag));
      }
    }
    return;
  }
  SculptSettingOverrides overrides = overrides_;
  overrides[k] = value;
  adopt(build(overrides, pins_, true));
  overrides_ = overrides;
  settings_[k] = value;
}

void SculptSession::undo(int client) {
  const auto last = std::find_if(undo_.rbegin(), undo_.rend(),
                                 [client](const Snapshot& s) { return s.client == client; });
  if (last == undo_.rend()) {
    throw make_error("undo: no drag of this client to undo");
  }
  const Snapshot snapshot = *last;
  simulation_->set_state(snapshot.q, snapshot.qd);
  if (drags_.contains(snapshot.drag)) {
    end_drag(snapshot.drag);
  }
  undo_.erase(std::next(last).base());
  diverged_.clear();
}

std::vector<std::string> SculptSession::save() const {
  std::vector<std::string> files;
  const System& system = simulation_->system();
  for (int i = 0; i < system.model_count(); ++i) {
    const std::string stem = output_file_stem(scene_.models[static_cast<std::size_t>(i)].name,
                                              "model" + std::to_string(i));
    if (const std::optional<Shape> shape = simulation_->shape(i)) {
      const std::filesystem::path path =
          output_file_path(options_.output_directory, stem + ".json");
      write_shape_file(path, *shape);
      files.push_back(path.string());
    }
    const std::filesystem::path path = output_file_path(options_.output_directory, stem + ".obj");
    export_mesh(simulation_->mesh(i, scene_.output.resolution), path);
    files.push_back(path.string());
    // assimp's OBJ writer puts the material beside the mesh
    if (const auto material = std::filesystem::path(path).replace_extension(".mtl");
        std::filesystem::is_regular_file(material)) {
      files.push_back(material.string());
    }
  }
  return files;
}

std::unique_ptr<SceneSimulation> SculptSession::build(const SculptSettingOverrides& overrides,
                                                      const std::vector<SculptPin>& pins,
                                                      bool keep_state) {
  auto simulation = std::make_unique<SceneSimulation>(sculpt_scene(scene_, overrides, pins));
  if (keep_state) {
    simulation->continue_from(*simulation_);
  }
  for (int i = 0; i < simulation->system().model_count(); ++i) {
    simulation->add_interactive_force(
        i,
        [this, i](const Model& model, double, ConstVectorRef q, ConstVectorRef, VectorRef force) {
          for (const auto& [id, drag] : drags_) {
            if (drag.push && drag.model == i) {
              model.add_point_force(q, drag.at, drag.vector, force);
            }
          }
        },
        "the pushes on " + scene_.models[static_cast<std::size_t>(i)].name);
  }
  return simulation;
}

void SculptSession::adopt(std::unique_ptr<SceneSimulation> simulation) {
  for (auto& [id, drag] : drags_) {
    if (!drag.push) {
      drag.spring = simulation->add_interactive_spring(
          drag.model, drag_spring(drag),
          "the drag " + std::to_string(id) + " of client " + std::to_string(drag.client) + " on " +
              scene_.models[static_cast<std::size_t>(drag.model)].name);
    }
  }
  simulation_ = std::move(simulation);
}

bool SculptSession::tick(double now) {
  if (!playing_ && pending_steps_ == 0) {
    return false;
  }
  const auto start = std::chrono::steady_clock::now();
  try {
    simulation_->step();
  } catch (const std::exception& error) {
    playing_ = false;
    pending_steps_ = 0;
    diverged_ = error.what();
    return false;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  step_seconds_ = step_seconds_ == 0.0 ? seconds : 0.9 * step_seconds_ + 0.1 * seconds;
  pending_steps_ = std::max(0, pending_steps_ - 1);
  step_times_.push_back(now);
  while (step_times_.front() < now - 1.0) {
    step_times_.pop_front();
  }
  return true;
}

std::string SculptSession::scene_message(int client) const {
  Json models = Json::array();
  const System& system = simulation_->system();
  for (int i = 0; i < system.model_count(); ++i) {
    const TriangleMesh mesh = simulation_->mesh(i, options_.resolution);
    Json triangles = Json::array();
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      triangles.insert(triangles.end(),
                       {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)});
    }
    Json uv = Json::array();
    for (Eigen::Index v = 0; v < mesh.uv.rows(); ++v) {
      uv.insert(uv.end(), {mesh.uv(v, 0), mesh.uv(v, 1)});
    }
    const ControlNet net = control_net(*simulation_, i);
    models.push_back({{"index", i},
                      {"name", scene_.models[static_cast<std::size_t>(i)].name},
                      {"kind", system.model(i).parametric_dimension() == 1 ? "curve" : "surface"},
                      {"vertex_count", mesh.vertex_count()},
                      {"triangles", std::move(triangles)},
                      {"uv", std::move(uv)},
                      {"control_net", net.points.rows() == 0 ? Json(nullptr)
                                                             : Json{{"count", net.points.rows()},
                                                                    {"lines", net.lines}}}});
  }
  Json settings = Json::object();
  for (std::size_t k = 0; k < settings_.size(); ++k) {
    settings[sculpt_setting_range(static_cast<SculptSetting>(k)).name] = settings_[k];
  }
  return dump({{"type", "scene"},
               {"client", client},
               {"models", std::move(models)},
               {"settings", std::move(settings)}});
}

std::string SculptSession::status_message(double now) const {
  const auto per_second = [now](const std::deque<double>& times) {
    return std::count_if(times.begin(), times.end(), [now](double t) { return t > now - 1.0; });
  };
  const EnergyBudget& budget = simulation_->energy_budget();
  const double spring = simulation_->system().spring_energy();
  Json settings = Json::object();
  for (std::size_t k = 0; k < settings_.size(); ++k) {
    settings[sculpt_setting_range(static_cast<SculptSetting>(k)).name] = settings_[k];
  }
  return dump({{"type", "status"},
               {"time", simulation_->system().time()},
               {"step", simulation_->steps_done()},
               {"kinetic", budget.kinetic_energy()},
               {"potential", budget.potential_energy()},
               {"spring", spring},
               {"energy", budget.kinetic_energy() + budget.potential_energy() + spring},
               {"step_ms", 1000.0 * step_seconds_},
               {"steps_per_second", per_second(step_times_)},
               {"frames_per_second", per_second(frame_times_)},
               {"playing", playing_},
               {"clients", client_count()},
               {"drags", drag_count()},
               {"pins", pin_count()},
               {"settings", std::move(settings)},
               {"diverged", diverged_}});
}

std::string SculptSession::frame(bool changed_only, double now) {
  const System& system = simulation_->system();
  std::vector<TriangleMesh> meshes;
  std::vector<int> indices;
  meshes.reserve(static_cast<std::size_t>(system.model_count()));
  for (int i = 0; i < system.model_count(); ++i) {
    Eigen::VectorXd& last = last_sent_[static_cast<std::size_t>(i)];
    const Eigen::VectorXd q = system.coordinates(i);
    if (changed_only && last.size() == q.size() && last == q) {
      continue;
    }
    if (changed_only) {
      last = q;
    }
    meshes.push_back(simulation_->mesh(i, options_.resolution));
    indices.push_back(i);
  }
  if (indices.empty()) {
    return {};
  }
  std::vector<SculptFrameModel> parts;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    parts.push_back({indices[k], &meshes[k], control_net(*simulation_, indices[k]).points});
  }
  if (changed_only) {
    ++frame_number_;
    frame_times_.push_back(now);
    while (frame_times_.front() < now - 1.0) {
      frame_times_.pop_front();
    }
  }
  return encode_sculpt_frame(frame_number_, parts);
}

std::string SculptSession::next_frame(double now) {
  return frame(true, now);
}

std::string SculptSession::full_frame() {
  return frame(false, 0.0);
}

}  // namespace dnurbs
