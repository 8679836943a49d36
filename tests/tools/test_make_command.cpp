// `dnurbs make`: shape files from the generators, flags read as JSON or comma lists, bad values
// exit 1 naming the key, bad command lines exit 2.
#include <filesystem>
#include <numbers>
#include <string>
#include <variant>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/io/shape_file.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/nurbs/shape_generators.h"
#include "tests/tools/run_dnurbs.h"

namespace dnurbs {
namespace {

using testing::fresh_directory;
using ::testing::HasSubstr;
using testing::run_dnurbs;

TEST(MakeCommand, WritesTheShapeFileOfTheGenerator) {
  const auto directory = fresh_directory("make");
  const std::string sheet = (directory / "sheet.json").string();
  const auto made =
      run_dnurbs("make plane " + sheet + " --size 3,2 --control-points 9,7 --degree '[3, 2]'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_EQ(made.out, sheet + ": nurbs_surface, 9 x 7 control points, degrees 3 x 2\n");
  EXPECT_EQ(shape_to_json(read_shape_file(sheet)),
            shape_to_json(Shape(greville_plane({3, 2}, {9, 7}, {3, 2}))));

  // A profile file, revolved by a quarter turn
  const std::string profile = (directory / "profile.json").string();
  write_shape_file(profile, Shape(half_circle_xz(2.0)));
  const std::string bowl = (directory / "bowl.json").string();
  const auto revolved =
      run_dnurbs("make revolve " + bowl + " --profile " + profile + " --angle-degrees 90");
  ASSERT_EQ(revolved.exit_code, 0) << revolved.err;
  EXPECT_EQ(shape_to_json(read_shape_file(bowl)),
            shape_to_json(Shape(revolve(half_circle_xz(2.0), std::numbers::pi / 2))));
  std::filesystem::remove_all(directory);
}

TEST(MakeCommand, BadValuesExitOneAndBadCommandLinesExitTwo) {
  const auto directory = fresh_directory("make_errors");
  const std::string out = (directory / "x.json").string();
  const auto negative = run_dnurbs("make sphere " + out + " --radius -1");
  EXPECT_EQ(negative.exit_code, 1);
  EXPECT_THAT(negative.err, HasSubstr("radius: expected a number > 0, got -1"));
  const auto unknown = run_dnurbs("make blob " + out);
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_THAT(unknown.err, HasSubstr("kind: expected one of line, plane, box"));
  const auto key = run_dnurbs("make box " + out + " --radius 2");
  EXPECT_EQ(key.exit_code, 1);
  EXPECT_THAT(key.err, HasSubstr("radius: unknown key for a \"box\" recipe"));
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_EQ(run_dnurbs("make").exit_code, 2);
  EXPECT_EQ(run_dnurbs("make plane").exit_code, 2);
  EXPECT_EQ(run_dnurbs("make plane " + out + " --size").exit_code, 2);
  EXPECT_EQ(run_dnurbs("make plane " + out + " --size 1,1 --size 2,2").exit_code, 2);
  EXPECT_EQ(run_dnurbs("make plane " + out + " extra.json").exit_code, 2);
  const auto help = run_dnurbs("make --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("usage: dnurbs make KIND OUT.json"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
