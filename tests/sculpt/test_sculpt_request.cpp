// Client messages parsed into requests: every type with its keys; the limits of the scene.

#include "dnurbs/sculpt/sculpt_request.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

SculptRequestLimits limits() {
  SculptRequestLimits l;
  l.models.push_back({2, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)});
  l.models.push_back({1, Eigen::Vector2d(-2, 0), Eigen::Vector2d(3, 0)});
  return l;
}

std::string error_of(const std::string& text) {
  try {
    parse_sculpt_request(text, limits());
  } catch (const SculptRequestError& error) {
    return error.what();
  }
  return "accepted";
}

TEST(SculptRequest, ReadsEveryTypeWithItsKeys) {
  const SculptRequest grab = parse_sculpt_request(
      R"({"type":"grab","id":5,"model":0,"at":[0.25,1],"target":[1,2,3]})", limits());
  EXPECT_EQ(grab.type, SculptRequestType::kGrab);
  EXPECT_EQ(grab.id, 5);
  EXPECT_EQ(grab.model, 0);
  EXPECT_EQ(*grab.at, Eigen::Vector2d(0.25, 1));
  EXPECT_EQ(*grab.target, Eigen::Vector3d(1, 2, 3));
  // A curve's material point is [u], within its own domain
  const SculptRequest push =
      parse_sculpt_request(R"({"type":"push","model":1,"at":[-1.5],"force":[0,0,-1]})", limits());
  EXPECT_EQ(*push.at, Eigen::Vector2d(-1.5, 0));
  EXPECT_EQ(*push.force, Eigen::Vector3d(0, 0, -1));
  const SculptRequest move =
      parse_sculpt_request(R"({"type":"move","drag":3,"at":[0.5],"force":[1,0,0]})", limits());
  EXPECT_EQ(move.drag, 3);
  EXPECT_FALSE(move.target);
  const SculptRequest set =
      parse_sculpt_request(R"({"type":"set","key":"dt","value":0.02})", limits());
  EXPECT_EQ(set.setting, SculptSetting::kDt);
  EXPECT_EQ(set.value, 0.02);
  const std::vector<std::pair<const char*, SculptRequestType>> bare = {
      {"play", SculptRequestType::kPlay}, {"pause", SculptRequestType::kPause},
      {"step", SculptRequestType::kStep}, {"reset", SculptRequestType::kReset},
      {"undo", SculptRequestType::kUndo}, {"save", SculptRequestType::kSave}};
  for (const auto& [name, type] : bare) {
    EXPECT_EQ(parse_sculpt_request(std::string(R"({"type":")") + name + "\"}", limits()).type,
              type);
  }
  EXPECT_EQ(parse_sculpt_request(R"({"type":"release","drag":0})", limits()).type,
            SculptRequestType::kRelease);
  EXPECT_EQ(parse_sculpt_request(R"({"type":"pin","model":1,"at":[3]})", limits()).type,
            SculptRequestType::kPin);
  EXPECT_EQ(parse_sculpt_request(R"({"type":"query","model":0,"at":[0,0]})", limits()).type,
            SculptRequestType::kQuery);
  EXPECT_EQ(parse_sculpt_request(R"({"type":"shape","model":1})", limits()).model, 1);
}

TEST(SculptRequest, RefusesWhatTheSceneCannotTake) {
  EXPECT_THAT(error_of(R"({"type":"pin","model":1,"at":[3.5]})"),
              HasSubstr("at[0]: 3.5 is outside the domain [-2, 3] of model 1"));
  EXPECT_THAT(error_of(R"({"type":"pin","model":1,"at":[0, 0]})"),
              HasSubstr("at: expected an array of 1 numbers"));
  EXPECT_THAT(error_of(R"({"type":"move","drag":1,"target":[0,0,0],"at":[]})"),
              HasSubstr("at: expected [u] or [u, v]"));
  EXPECT_THAT(error_of(R"({"type":"move","drag":1,"target":[0,0,0],"force":[0,0,0]})"),
              HasSubstr("exactly one of"));
  EXPECT_THAT(error_of(R"({"type":"set","key":"dt","value":1e-5})"),
              HasSubstr("dt must be in [0.0001, 0.1"));
  EXPECT_THAT(error_of(R"({"type":"release","drag":-3})"), HasSubstr("drag: expected an integer"));
  EXPECT_THAT(error_of(R"({"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,1e999]})"),
              HasSubstr("malformed JSON"));
  EXPECT_EQ(sculpt_setting_range(SculptSetting::kDensity).open_min, true);
}

}  // namespace
}  // namespace dnurbs
