// Binary frames: what is encoded is decoded, to float precision; a damaged frame is refused.

#include "dnurbs/sculpt/sculpt_frame.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

TEST(SculptFrame, RoundTripsToFloatPrecision) {
  TriangleMesh mesh;
  mesh.vertices = Eigen::MatrixX3d::Random(7, 3);
  mesh.normals = Eigen::MatrixX3d::Random(7, 3);
  const Eigen::MatrixX3d control = Eigen::MatrixX3d::Random(4, 3);
  const std::string frame = encode_sculpt_frame(42, {{3, &mesh, control}, {5, &mesh, {}}});
  // Header 12 bytes; per model 12 + 24 n + 12 c bytes
  EXPECT_EQ(frame.size(), 12U + (12 + 24 * 7 + 12 * 4) + (12 + 24 * 7));
  const DecodedSculptFrame decoded = decode_sculpt_frame(frame);
  EXPECT_EQ(decoded.frame_number, 42U);
  ASSERT_EQ(decoded.models.size(), 2U);
  EXPECT_EQ(decoded.models[0].index, 3);
  EXPECT_EQ(decoded.models[1].index, 5);
  EXPECT_LT((decoded.models[0].positions - mesh.vertices).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((decoded.models[0].normals - mesh.normals).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((decoded.models[0].control_points - control).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(decoded.models[1].control_points.rows(), 0);
}

TEST(SculptFrame, RefusesDamagedFrames) {
  TriangleMesh mesh;
  mesh.vertices = Eigen::MatrixX3d::Zero(2, 3);
  mesh.normals = Eigen::MatrixX3d::Zero(2, 3);
  const std::string frame = encode_sculpt_frame(1, {{0, &mesh, {}}});
  EXPECT_THROW(decode_sculpt_frame("XNF1" + frame.substr(4)), Error);
  try {
    decode_sculpt_frame(frame.substr(0, frame.size() - 1));
    FAIL() << "a truncated frame was accepted";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("truncated at byte 48"));
  }
  EXPECT_THROW(decode_sculpt_frame(frame + "x"), Error);
  mesh.normals.resize(1, 3);
  EXPECT_THROW(encode_sculpt_frame(1, {{0, &mesh, {}}}), Error);
}

}  // namespace
}  // namespace dnurbs
