// `dnurbs info` on the triangular D-NURBS example scenes: the model's coordinates, the fixed
// border, constant Kronecker matrices and the saving of fixed weights.

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

TEST(InfoCommand, DescribesTriangularDNurbsSurfaces) {
  const testing::CommandResult info =
      testing::run_dnurbs("info " + (kExamples / "triangular_l_shape.json").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  // L-shape, 3 cells per unit: 27 cells, 54 triangles of 6 quadratic B-splines, 3 coordinates each
  EXPECT_THAT(info.out, HasSubstr("sheet (triangular_dnurbs_surface): 972 coordinates"));
  EXPECT_THAT(info.out, HasSubstr("x, y, z share one scalar matrix (S (x) I_3)"));
  EXPECT_THAT(info.out, HasSubstr("saved: fixed weights (naive: free weights)"));
  EXPECT_THAT(info.out, HasSubstr("forces: 3 (1 pressure, 2 spring)"));
}

}  // namespace
}  // namespace dnurbs
