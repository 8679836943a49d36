// Tests of tools/info_command.cpp beyond the demo (tests/tools/test_run_command.cpp): a swung
// surface is reported with its coordinates against the tensor-product D-NURBS surface of the same
// shape, and the report says when the chosen model costs more per solve than its naive path; the
// triangular D-NURBS example shows its coordinates, constant Kronecker matrices and the saving of
// fixed weights.

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/tools/run_dnurbs.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kExamples =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes";

TEST(InfoCommand, SwungSurfaceShowsItsCoordinatesAgainstTheTensorProductTwin) {
  // The egg: 7 x 8 control points, 2 (7 + 8) = 30 coordinates, 18 held (the poles' x and the
  // trajectory); its twin has 3 x 56 = 168, constant matrices.
  const testing::CommandResult egg =
      testing::run_dnurbs("info " + (kExamples / "swung_egg.json").string());
  ASSERT_EQ(egg.exit_code, 0) << egg.err;
  EXPECT_THAT(egg.out, HasSubstr("egg (swung_surface): 30 coordinates, 30 velocities, 18 fixed, "
                                 "12 active"));
  EXPECT_THAT(egg.out, HasSubstr("state-dependent (assembled and factored every step)"));
  EXPECT_THAT(egg.out,
              HasSubstr("saved: swung profile and trajectory coordinates (naive: the "
                        "tensor-product D-NURBS surface of the same shape, 7 x 8 control points): "
                        "12 instead of 168 active coordinates, state-dependent instead of "
                        "constant matrices, one solve"));
  // The toroid: 8 x 8 control points of which the profile's (16 coordinates) are held; 16
  // active swung coordinates re-factored every step against the twin's 192 back-substituted:
  // the estimate says which is cheaper either way.
  const testing::CommandResult toroid =
      testing::run_dnurbs("info " + (kExamples / "swung_toroid.json").string());
  ASSERT_EQ(toroid.exit_code, 0) << toroid.err;
  EXPECT_THAT(toroid.out, HasSubstr("toroid (swung_surface): 32 coordinates"));
  EXPECT_THAT(toroid.out, ::testing::ContainsRegex("one solve [0-9.]+x (cheaper|more expensive)"));
}

TEST(InfoCommand, DescribesTriangularDNurbsSurfaces) {
  const testing::CommandResult info =
      testing::run_dnurbs("info " + (kExamples / "triangular_l_shape.json").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  // L-shape, 3 cells per unit: 27 cells, 54 triangles of 6 quadratic B-splines, 3 coordinates each
  EXPECT_THAT(info.out, HasSubstr("sheet (triangular_dnurbs_surface): 972 coordinates"));
  EXPECT_THAT(info.out, HasSubstr("x, y, z share one scalar matrix (S (x) I_3)"));
  EXPECT_THAT(info.out, HasSubstr("saved: fixed weights (naive: free weights)"));
  EXPECT_THAT(info.out, HasSubstr("forces: 3 (1 pressure, 2 spring)"));
  EXPECT_THAT(info.out, ::testing::Not(HasSubstr("obstacles:")));  // it has none
}

TEST(InfoCommand, ListsTheObstaclesAndTheContactMethod) {
  // The rug falls on a ground plane, a box and a sphere, with projection contact
  const testing::CommandResult info =
      testing::run_dnurbs("info " + (kExamples / "rug_on_obstacles.json").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("obstacles: 3 (1 box, 1 plane, 1 sphere), projection contact"));
}

TEST(InfoCommand, AFactorWithoutOffDiagonalEntriesHasNoCostRatio) {
  // The face's one dynamic parameter (jaw_open; the smile is keyed): a 1 x 1 factor touches no
  // entries on either path, which once printed the ratio 0 / 0 as "-nanx"
  const testing::CommandResult info =
      testing::run_dnurbs("info " + (kExamples / "deformation_field.json").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("the naive paths would touch 0 (the same)"));
  EXPECT_THAT(info.out, ::testing::Not(HasSubstr("nan")));
}

}  // namespace
}  // namespace dnurbs
