// The sculpting session: every message type acts as documented (docs/serve.md), every rejected
// message leaves the state exactly as it was, drags and pushes follow the same trajectory as the
// scene's own springs and point forces, and a client that leaves takes its drags with it.

#include "dnurbs/sculpt/sculpt_session.h"

#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/sculpt/sculpt_frame.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;
using ::testing::HasSubstr;

const std::filesystem::path kScenes =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";

// The default demo without its scripted forces (as `dnurbs serve` runs it), with `forces` (JSON
// array text) added.
Scene demo_scene(const std::string& forces = "[]") {
  Json json = Json::parse(scene_to_json(read_scene_file(kScenes / "hat_demo.json")));
  Json kept = Json::array();
  for (const Json& force : json["forces"]) {
    if (force["type"] == "gravity") {
      kept.push_back(force);
    }
  }
  for (const Json& force : Json::parse(forces)) {
    kept.push_back(force);
  }
  json["forces"] = kept;
  return parse_scene_json(json.dump(), "<test demo>");
}

SculptSessionOptions options(const std::string& folder = "sculpt_session_out") {
  SculptSessionOptions o;
  o.output_directory = std::filesystem::temp_directory_path() / folder;
  o.resolution = 6;
  return o;
}

Json only_reply(const SculptReply& reply) {
  EXPECT_EQ(reply.messages.size(), 1U);
  return reply.messages.empty() ? Json() : Json::parse(reply.messages.front());
}

// Everything a message could change.
struct SessionState {
  Eigen::VectorXd q;
  Eigen::VectorXd qd;
  double time = 0.0;
  int steps = 0;
  int drags = 0;
  int pins = 0;
  bool playing = false;
  std::vector<double> settings;
  int springs = 0;
  bool operator==(const SessionState&) const = default;
};

SessionState state_of(const SculptSession& session) {
  const System& system = session.simulation().system();
  SessionState s;
  s.q = system.coordinates();
  s.qd = system.velocities();
  s.time = system.time();
  s.steps = session.simulation().steps_done();
  s.drags = session.drag_count();
  s.pins = session.pin_count();
  s.playing = session.playing();
  for (int k = 0; k < 6; ++k) {
    s.settings.push_back(session.setting(static_cast<SculptSetting>(k)));
  }
  for (int id = 0; id < system.spring_id_count(); ++id) {
    s.springs += system.has_spring(id) ? 1 : 0;
  }
  return s;
}

Eigen::Vector3d point(SculptSession& session, int client, double u, double v) {
  const Json reply = only_reply(
      session.handle(client, Json{{"type", "query"}, {"model", 0}, {"at", {u, v}}}.dump(), 0.0));
  return {reply["position"][0].get<double>(), reply["position"][1].get<double>(),
          reply["position"][2].get<double>()};
}

TEST(SculptSession, EveryRejectedMessageIsAnsweredByAnErrorAndChangesNothing) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  const int other = session.connect();
  // A drag of the other client, and a few steps, so that there is state to disturb
  session.handle(other, R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,0.3]})", 0.0);
  for (int i = 0; i < 5; ++i) {
    session.tick(0.0);
  }
  session.handle(client, R"({"type":"pause"})", 0.0);
  const SessionState before = state_of(session);
  const std::vector<std::pair<std::string, std::string>> rejected = {
      {"not json", "malformed JSON"},
      {"[1, 2]", "expected a JSON object"},
      {"{}", "missing key \"type\""},
      {R"({"type":"explode"})", "unknown message type"},
      {R"({"type":7})", "unknown message type"},
      {R"({"type":"play","extra":1})", "unknown key \"extra\""},
      {R"({"type":"play","id":"seven"})", "id: expected an integer"},
      {R"({"type":"grab","model":0,"at":[0.5,0.5]})", "missing key \"target\""},
      {R"({"type":"grab","model":4,"at":[0.5,0.5],"target":[0,0,0]})",
       "model: expected an integer in [0, 3], got 4"},
      {R"({"type":"grab","model":-1,"at":[0.5,0.5],"target":[0,0,0]})", "got -1"},
      {R"({"type":"grab","model":0.5,"at":[0.5,0.5],"target":[0,0,0]})", "expected an integer"},
      {R"({"type":"grab","model":0,"at":[0.5,1.5],"target":[0,0,0]})",
       "at[1]: 1.5 is outside the domain [0, 1]"},
      {R"({"type":"grab","model":0,"at":[0.5],"target":[0,0,0]})",
       "at: expected an array of 2 numbers"},
      {R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,"NaN",0]})",
       "target[1]: expected a number"},
      {R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0]})",
       "target: expected an array of 3"},
      {R"({"type":"push","model":0,"at":[0.5,0.5],"force":[1e308,1e308,"x"]})", "force[2]"},
      {R"({"type":"move","drag":1,"target":[0,0,1]})", "no drag 1 of this client"},
      {R"({"type":"move","drag":99,"target":[0,0,1]})", "no drag 99"},
      {R"({"type":"move","drag":1})", "exactly one of"},
      {R"({"type":"release","drag":1})", "no drag 1 of this client"},
      {R"({"type":"pin","model":0,"at":[-0.1,0.5]})", "outside the domain"},
      {R"({"type":"set","key":"gravity","value":1})", "key: expected one of stiffness"},
      {R"({"type":"set","key":"stiffness","value":0})", "stiffness must be in (0, 1000000]"},
      {R"({"type":"set","key":"stiffness","value":2e6})", "stiffness must be in"},
      {R"({"type":"set","key":"tension","value":-1})", "tension must be in [0, 10000]"},
      {R"({"type":"set","key":"rigidity","value":1e5})", "rigidity must be in"},
      {R"({"type":"set","key":"density","value":0})", "density must be in (0, 10000]"},
      {R"({"type":"set","key":"damping","value":-0.5})", "damping must be in"},
      {R"({"type":"set","key":"dt","value":0.5})", "dt must be in [0.0001, 0.1"},
      {R"({"type":"set","key":"dt"})", "missing key \"value\""},
      {R"({"type":"undo"})", "no drag of this client to undo"},
      {R"({"type":"shape","model":2})", "has no exact shape"},
      {"{\"type\":\"play\",\"\xff\xfe\":1}", "malformed JSON"},
      {std::string(20000, ' ') + "{}", "message of 20002 bytes refused: at most 16384"},
  };
  for (const auto& [message, expected] : rejected) {
    SCOPED_TRACE(message.substr(0, 80));
    const Json reply = only_reply(session.handle(client, message, 0.0));
    EXPECT_EQ(reply["type"], "error");
    EXPECT_THAT(reply["message"].get<std::string>(), HasSubstr(expected));
    EXPECT_TRUE(state_of(session) == before);
  }
  // The id of a rejected message is echoed so that a client can match the error
  const Json reply =
      only_reply(session.handle(client, R"({"type":"set","id":12,"key":"dt","value":1})", 0.0));
  EXPECT_EQ(reply["id"], 12);
  EXPECT_EQ(reply["request"], "set");
}

TEST(SculptSession, AFloodIsRefusedBeyondTheRateWithOneWarningASecond) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  int answered = 0;
  int warnings = 0;
  for (int i = 0; i < 1000; ++i) {
    const SculptReply reply = session.handle(client, R"({"type":"pause"})", 5.0);
    answered += reply.status_changed ? 1 : 0;
    warnings += reply.messages.empty() ? 0 : 1;
  }
  // A bucket of 200 tokens, none refilled at the same instant
  EXPECT_EQ(answered, 200);
  EXPECT_EQ(warnings, 1);
  // Half a second later, 100 more
  answered = 0;
  for (int i = 0; i < 1000; ++i) {
    answered += session.handle(client, R"({"type":"pause"})", 5.5).status_changed ? 1 : 0;
  }
  EXPECT_EQ(answered, 100);
}

// A drag held still is the scene's own spring: the same trajectory to rounding.
TEST(SculptSession, AHeldDragFollowsTheTrajectoryOfTheScenesSpring) {
  const Scene scripted = demo_scene(
      R"([{"type":"spring","model":"hat","at":[0.4,0.55],"stiffness":300,"target":[0.1,0.2,0.6]}])");
  SceneSimulation reference(scripted);
  SculptSessionOptions o = options();
  o.stiffness = 300.0;
  SculptSession session(demo_scene(), o);
  const int client = session.connect();
  const Json grabbed = only_reply(session.handle(
      client, R"({"type":"grab","model":0,"at":[0.4,0.55],"target":[0.1,0.2,0.6]})", 0.0));
  EXPECT_EQ(grabbed["type"], "grabbed");
  for (int i = 0; i < 100; ++i) {
    reference.step();
    ASSERT_TRUE(session.tick(0.0));
  }
  const Eigen::VectorXd q = session.simulation().system().coordinates();
  const Eigen::VectorXd q_ref = reference.system().coordinates();
  EXPECT_LT((q - q_ref).norm(), 1e-12 * q_ref.norm());
  // The crown rose toward the target
  EXPECT_GT(point(session, client, 0.4, 0.55).z(), 0.1);
}

TEST(SculptSession, APushIsTheScenesPointForce) {
  SceneSimulation reference(
      demo_scene(R"([{"type":"point","model":"hat","at":[0.5,0.5],"force":[0,0,4]}])"));
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  only_reply(
      session.handle(client, R"({"type":"push","model":0,"at":[0.5,0.5],"force":[0,0,4]})", 0.0));
  for (int i = 0; i < 50; ++i) {
    reference.step();
    session.tick(0.0);
  }
  const Eigen::VectorXd q_ref = reference.system().coordinates();
  EXPECT_LT((session.simulation().system().coordinates() - q_ref).norm(), 1e-12 * q_ref.norm());
}

TEST(SculptSession, MovingADragMovesTheTargetAndTheMaterialPoint) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  const int drag = only_reply(session.handle(
      client, R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,0]})", 0.0))["drag"];
  const std::string move =
      Json{{"type", "move"}, {"drag", drag}, {"at", {0.3, 0.6}}, {"target", {0.2, 0.1, 0.4}}}
          .dump();
  EXPECT_TRUE(session.handle(client, move, 0.0).messages.empty());
  const System& system = session.simulation().system();
  int live = -1;
  for (int id = 0; id < system.spring_id_count(); ++id) {
    live = system.has_spring(id) ? id : live;
  }
  const SpringState spring = system.spring_state(live, system.time());
  EXPECT_EQ(spring.parameter, Eigen::Vector2d(0.3, 0.6));
  EXPECT_EQ(spring.target, Eigen::Vector3d(0.2, 0.1, 0.4));
  EXPECT_EQ(spring.stiffness, 100.0);
  // A new stiffness reaches the live spring
  session.handle(client, R"({"type":"set","key":"stiffness","value":2500})", 0.0);
  EXPECT_EQ(system.spring_state(live, system.time()).stiffness, 2500.0);
  // A push cannot be moved with a target, nor a spring with a force
  const Json wrong = only_reply(session.handle(
      client, Json{{"type", "move"}, {"drag", drag}, {"force", {0, 0, 1}}}.dump(), 0.0));
  EXPECT_THAT(wrong["message"].get<std::string>(), HasSubstr("is a spring"));
}

TEST(SculptSession, AClientThatLeavesMidDragLeavesNoSpringBehind) {
  SculptSession session(demo_scene(), options());
  const int stays = session.connect();
  const int leaves = session.connect();
  session.handle(stays, R"({"type":"grab","model":0,"at":[0.3,0.3],"target":[0,0,0.2]})", 0.0);
  session.handle(leaves, R"({"type":"grab","model":0,"at":[0.6,0.6],"target":[0,0,0.2]})", 0.0);
  session.handle(leaves, R"({"type":"push","model":1,"at":[0.5,0.5],"force":[0,0,1]})", 0.0);
  EXPECT_EQ(session.drag_count(), 3);
  session.disconnect(leaves);
  EXPECT_EQ(session.drag_count(), 1);
  EXPECT_EQ(session.client_count(), 1);
  EXPECT_EQ(state_of(session).springs, 1);
  // Its id is gone: its messages are refused
  EXPECT_EQ(only_reply(session.handle(leaves, R"({"type":"play"})", 0.0))["type"], "error");
}

TEST(SculptSession, APinHoldsItsPointWhileTheSheetIsPulled) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  const Json pinned =
      only_reply(session.handle(client, R"({"type":"pin","model":0,"at":[0.4,0.4]})", 0.0));
  EXPECT_EQ(pinned["pin"], 0);
  const Eigen::Vector3d held(pinned["position"][0], pinned["position"][1], pinned["position"][2]);
  EXPECT_EQ(held, session.simulation().system().position(0, Eigen::Vector2d(0.4, 0.4)));
  session.handle(client, R"({"type":"set","key":"stiffness","value":1000})", 0.0);
  session.handle(client, R"({"type":"grab","model":0,"at":[0.55,0.55],"target":[0,0,0.8]})", 0.0);
  Eigen::VectorXd free_sheet;
  {
    SculptSession unpinned(demo_scene(), options());
    const int c = unpinned.connect();
    unpinned.handle(c, R"({"type":"set","key":"stiffness","value":1000})", 0.0);
    unpinned.handle(c, R"({"type":"grab","model":0,"at":[0.55,0.55],"target":[0,0,0.8]})", 0.0);
    for (int i = 0; i < 100; ++i) {
      unpinned.tick(0.0);
    }
    free_sheet = unpinned.simulation().system().position(0, Eigen::Vector2d(0.4, 0.4));
  }
  for (int i = 0; i < 100; ++i) {
    session.tick(0.0);
  }
  const Eigen::Vector3d x = session.simulation().system().position(0, Eigen::Vector2d(0.4, 0.4));
  // Unpinned, the point rises by a tenth or more; pinned, Baumgarte keeps its drift tiny
  EXPECT_GT(free_sheet.z() - held.z(), 0.1);
  EXPECT_LT((x - held).norm(), 1e-3 * (free_sheet - held).norm());
  EXPECT_EQ(session.pin_count(), 1);
}

TEST(SculptSession, AMaterialChangeKeepsTheStateAndStiffensTheSheet) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  session.handle(client, R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,0.5]})", 0.0);
  for (int i = 0; i < 20; ++i) {
    session.tick(0.0);
  }
  const SessionState before = state_of(session);
  const auto elastic_energy_at_tension = [&](double tension) {
    const SculptReply reply = session.handle(
        client, Json{{"type", "set"}, {"key", "tension"}, {"value", tension}}.dump(), 0.0);
    EXPECT_TRUE(reply.status_changed);
    return session.simulation().energy_budget().potential_energy();
  };
  // The elastic energy at one shape is affine in the tension (a10 = a01 = tension on the hat
  // and the torus): E(t) = E(0) + t (E(1) - E(0))
  const double e0 = elastic_energy_at_tension(0.0);
  const double e1 = elastic_energy_at_tension(1.0);
  const double e50 = elastic_energy_at_tension(50.0);
  EXPECT_GT(e1, e0);
  EXPECT_NEAR(e50 - e0, 50.0 * (e1 - e0), 1e-10 * e50);
  const SessionState after = state_of(session);
  EXPECT_EQ(after.q, before.q);
  EXPECT_EQ(after.qd, before.qd);
  EXPECT_EQ(after.time, before.time);
  EXPECT_EQ(after.steps, before.steps);
  EXPECT_EQ(after.springs, 1);  // the drag's spring was carried to the new simulation
  EXPECT_EQ(session.setting(SculptSetting::kTension), 50.0);
}

TEST(SculptSession, UndoReturnsToTheStateBeforeTheLastDrag) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  for (int i = 0; i < 10; ++i) {
    session.tick(0.0);
  }
  const SessionState before = state_of(session);
  session.handle(client, R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,0.5]})", 0.0);
  for (int i = 0; i < 30; ++i) {
    session.tick(0.0);
  }
  session.handle(client, R"({"type":"undo"})", 0.0);
  const SessionState after = state_of(session);
  EXPECT_EQ(after.q, before.q);
  EXPECT_EQ(after.qd, before.qd);
  EXPECT_EQ(after.drags, 0);
  EXPECT_EQ(after.springs, 0);
}

TEST(SculptSession, ResetReturnsToTheScenesInitialStateWithoutDragsOrPins) {
  SculptSession session(demo_scene(), options());
  const int client = session.connect();
  const Eigen::VectorXd q0 = session.simulation().system().coordinates();
  session.handle(client, R"({"type":"pin","model":0,"at":[0.4,0.4]})", 0.0);
  session.handle(client, R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,0.5]})", 0.0);
  for (int i = 0; i < 10; ++i) {
    session.tick(0.0);
  }
  EXPECT_NE(session.simulation().system().coordinates(), q0);
  session.handle(client, R"({"type":"reset"})", 0.0);
  EXPECT_EQ(session.simulation().system().coordinates(), q0);
  EXPECT_EQ(session.simulation().steps_done(), 0);
  EXPECT_EQ(session.drag_count(), 0);
  EXPECT_EQ(session.pin_count(), 0);
  EXPECT_EQ(session.simulation().constraints().constraint_count(), 2);  // the pendulum's joints
}

TEST(SculptSession, SaveWritesTheCurrentShapesIntoTheOutputFolderOnly) {
  const SculptSessionOptions o = options("sculpt_session_save");
  std::filesystem::remove_all(o.output_directory);
  SculptSession session(demo_scene(), o);
  const int client = session.connect();
  session.handle(client, R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,0.5]})", 0.0);
  for (int i = 0; i < 10; ++i) {
    session.tick(0.0);
  }
  const Json saved = only_reply(session.handle(client, R"({"type":"save","id":3})", 0.0));
  EXPECT_EQ(saved["type"], "saved");
  EXPECT_EQ(saved["files"].size(), 10U);  // hat and torus: shape, OBJ, MTL; link and bob: OBJ, MTL
  for (const Json& file : saved["files"]) {
    EXPECT_EQ(std::filesystem::path(file.get<std::string>()).parent_path(), o.output_directory);
  }
  const Shape hat = read_shape_file(o.output_directory / "hat.json");
  const Json shape = only_reply(session.handle(client, R"({"type":"shape","model":0})", 0.0));
  EXPECT_EQ(Json::parse(shape_to_json(hat)), shape["shape"]);
  EXPECT_EQ(std::get<NurbsSurface>(hat).control_points(),
            std::get<NurbsSurface>(*session.simulation().shape(0)).control_points());
  EXPECT_TRUE(std::filesystem::is_regular_file(o.output_directory / "bob.obj"));
}

TEST(SculptSession, ADivergingStepPausesWithTheReportAndKeepsTheLastGoodState) {
  SculptSession session(read_scene_file(kScenes / "diverging_sheet.json"), options());
  int steps = 0;
  while (session.tick(0.0)) {
    ASSERT_LT(++steps, 1000);
  }
  EXPECT_FALSE(session.playing());
  EXPECT_THAT(session.diverged(), HasSubstr("newmark_gamma"));
  EXPECT_EQ(session.simulation().steps_done(), steps);
  const Json status = Json::parse(session.status_message(0.0));
  EXPECT_EQ(status["diverged"], session.diverged());
  EXPECT_EQ(status["playing"], false);
}

TEST(SculptSession, FramesCarryOnlyTheShapesThatChanged) {
  SculptSession session(demo_scene(), options());
  const DecodedSculptFrame first = decode_sculpt_frame(session.next_frame(0.0));
  ASSERT_EQ(first.models.size(), 4U);
  EXPECT_TRUE(session.next_frame(0.0).empty());  // nothing moved
  std::vector<Eigen::VectorXd> before;
  const System& system = session.simulation().system();
  for (int i = 0; i < 4; ++i) {
    before.push_back(system.coordinates(i));
  }
  session.tick(0.0);
  // Gravity moves the pendulum; the unloaded hat and torus move by rounding at most, and a
  // model whose coordinates did not change is not sent
  const DecodedSculptFrame second = decode_sculpt_frame(session.next_frame(0.0));
  std::vector<int> changed;
  for (int i = 0; i < 4; ++i) {
    if (system.coordinates(i) != before[static_cast<std::size_t>(i)]) {
      changed.push_back(i);
    }
  }
  std::vector<int> sent;
  for (const auto& model : second.models) {
    sent.push_back(model.index);
  }
  EXPECT_EQ(sent, changed);
  EXPECT_LT(sent.size(), 4U);
  EXPECT_EQ(sent.back(), 3);
  EXPECT_EQ(second.frame_number, first.frame_number + 1);
  const TriangleMesh bob = session.simulation().mesh(3, 6);
  EXPECT_LT((second.models.back().positions - bob.vertices).cwiseAbs().maxCoeff(),
            1e-6 * bob.vertices.cwiseAbs().maxCoeff());  // float32
  // The hat's control net: 7 x 7 points
  EXPECT_EQ(first.models[0].control_points.rows(), 49);
  EXPECT_EQ(first.models[2].control_points.rows(), 0);
}

TEST(SculptSession, TheSceneMessageDescribesEveryModelsTopology) {
  SculptSession session(demo_scene(), options());
  const Json scene = Json::parse(session.scene_message(session.connect()));
  ASSERT_EQ(scene["models"].size(), 4U);
  const Json& hat = scene["models"][0];
  EXPECT_EQ(hat["name"], "hat");
  EXPECT_EQ(hat["kind"], "surface");
  const TriangleMesh mesh = session.simulation().mesh(0, 6);
  EXPECT_EQ(hat["vertex_count"], mesh.vertex_count());
  EXPECT_EQ(hat["triangles"].size(), 3U * static_cast<std::size_t>(mesh.triangle_count()));
  EXPECT_EQ(hat["uv"].size(), 2U * static_cast<std::size_t>(mesh.vertex_count()));
  // A 7 x 7 grid has 2 * 7 * 6 segments
  EXPECT_EQ(hat["control_net"]["lines"].size(), 2U * 84U);
  EXPECT_TRUE(scene["models"][2]["control_net"].is_null());
  EXPECT_EQ(scene["settings"]["tension"], 1.0);  // the hat's a10
  EXPECT_EQ(scene["settings"]["stiffness"], 100.0);
}

}  // namespace
}  // namespace dnurbs
