#pragma once
// A sculpting session (docs/serve.md): one scene simulated for any number of clients who grab
// its shapes with mouse springs (implicit in the step: dynamics/core/spring.h), push them with
// point forces, pin points with point constraints (Terzopoulos, Deformable Models: Classic,
// Topology-Adaptive and Generalized Formulations, eqs. 1.39-1.40), change the material and the
// time step, undo a drag, reset and save. It turns the clients' text messages into these actions
// (every message validated first: sculpt/sculpt_request.h; a refused one changes nothing), steps
// the simulation, and writes the status and the frames the clients receive.
//
// The session is not thread-safe: the server calls it from its simulation thread only.
// Material and time-step changes and pins rebuild the simulation from the scene with the change
// applied and carry the state over (SceneSimulation::continue_from); a rebuild that fails leaves
// the session as it was.

#include <array>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/sculpt/sculpt_request.h"
#include "dnurbs/sculpt/sculpt_scene.h"

namespace dnurbs {

struct SculptSessionOptions {
  /// `save` writes here only (created when first needed).
  std::filesystem::path output_directory = "dnurbs-out";
  /// Mesh segments per direction of the frames (times each model's resolution_scale).
  int resolution = 24;
  /// Messages a second a client may send (a token bucket of this capacity); more are refused.
  double messages_per_second = 200.0;
  /// Spring stiffness of new drags until a client sets it.
  double stiffness = 100.0;
};

/// What handling one message produced.
struct SculptReply {
  std::vector<std::string> messages;  ///< JSON texts for the client that sent it
  bool status_changed = false;        ///< every client should get a status now
};

class SculptSession {
 public:
  /// Builds the simulation; throws Error (as SceneSimulation does) for a bad scene and for bad
  /// options (a resolution outside [3, 256], a non-positive message rate or stiffness).
  SculptSession(Scene scene, SculptSessionOptions options);
  SculptSession(const SculptSession&) = delete;
  SculptSession& operator=(const SculptSession&) = delete;
  ~SculptSession();

  /// A new client; returns its id.
  int connect();
  /// The client leaves: its drags and pushes are removed.
  void disconnect(int client);
  int client_count() const { return static_cast<int>(clients_.size()); }

  /// Handles one text message of `client` at `now` (seconds of a steady clock). Never throws
  /// for a bad message: it is answered by {"type": "error", ...} and changes nothing.
  SculptReply handle(int client, std::string_view text, double now);

  /// Advances one step when playing or when a `step` is pending; returns true if it stepped. A
  /// diverging step pauses the session and puts the report in the status (the state is the last
  /// good one, SceneSimulation::step).
  bool tick(double now);

  /// {"type": "scene", ...}: the models' topology, parameters and control nets, the settings.
  std::string scene_message(int client) const;
  /// {"type": "status", ...} at `now`.
  std::string status_message(double now) const;
  /// The binary frame (sculpt/sculpt_frame.h) of the models whose coordinates changed since the
  /// last frame (all of them the first time); empty when none did.
  std::string next_frame(double now);
  /// A frame of every model (for a client that just connected); changes nothing.
  std::string full_frame();

  const SceneSimulation& simulation() const { return *simulation_; }
  bool playing() const { return playing_; }
  int drag_count() const { return static_cast<int>(drags_.size()); }
  int pin_count() const { return static_cast<int>(pins_.size()); }
  double setting(SculptSetting setting) const {
    return settings_[static_cast<std::size_t>(setting)];
  }
  /// The divergence report of the last diverged step ("" if none since the last play).
  const std::string& diverged() const { return diverged_; }

 private:
  struct Drag {
    int client = 0;
    int model = 0;
    bool push = false;
    Eigen::Vector2d at = Eigen::Vector2d::Zero();
    Eigen::Vector3d vector = Eigen::Vector3d::Zero();  ///< spring target or push force
    int spring = -1;                                   ///< the simulation's spring id
  };
  struct Snapshot {
    int client = 0;
    int drag = -1;  ///< the drag that began after it
    Eigen::VectorXd q;
    Eigen::VectorXd qd;
  };
  struct Client {
    double tokens = 0.0;
    double last_refill = 0.0;
    double last_flood_warning = -1e300;
  };

  void apply(int client, const SculptRequest& request, SculptReply& reply);
  int begin_drag(int client, const SculptRequest& request);
  void move_drag(int client, const SculptRequest& request);
  void end_drag(int id);
  void change_setting(SculptSetting setting, double value);
  // Back to the state before the client's last drag began (that drag ended).
  void undo(int client);
  std::vector<std::string> save() const;
  // A simulation of the scene with these overrides and pins (sculpt/sculpt_scene.h), the pushes
  // and active drags attached (their spring ids set in drags_ only when `commit`); with
  // `keep_state`, continued from the current one. Throws Error and changes nothing on failure.
  std::unique_ptr<SceneSimulation> build(const SculptSettingOverrides& overrides,
                                         const std::vector<SculptPin>& pins, bool keep_state);
  // Swaps in a simulation from build: re-attaches the drags' springs.
  void adopt(std::unique_ptr<SceneSimulation> simulation);
  Spring drag_spring(const Drag& drag) const;
  void add_pushes(int model, ConstVectorRef q, VectorRef force) const;
  bool take_token(Client& client, double now) const;
  // The frame of every model, or of those changed since the last (then remembered as sent).
  std::string frame(bool changed_only, double now);

  Scene scene_;
  SculptSessionOptions options_;
  SculptRequestLimits limits_;
  SculptSettingOverrides overrides_;  ///< the settings clients changed
  std::array<double, 6> settings_{};  ///< every setting's current value
  std::unique_ptr<SceneSimulation> simulation_;
  std::map<int, Client> clients_;
  int next_client_ = 1;
  std::map<int, Drag> drags_;
  int next_drag_ = 1;
  std::vector<SculptPin> pins_;
  std::vector<Snapshot> undo_;
  bool playing_ = true;
  int pending_steps_ = 0;
  std::string diverged_;
  std::vector<Eigen::VectorXd> last_sent_;  ///< each model's coordinates in the last frame
  std::uint32_t frame_number_ = 0;
  double step_seconds_ = 0.0;  ///< exponential mean of the measured step time
  std::deque<double> step_times_;
  std::deque<double> frame_times_;
};

}  // namespace dnurbs
