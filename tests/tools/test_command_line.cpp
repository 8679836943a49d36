// The command-line parsing of every dnurbs subcommand (tools/command_line.h, CLI11): exit code 2
// with a message naming the option and the value for a bad command line, help that wins over
// errors, integers in decimal, negative numbers as values.

#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "tests/tools/run_dnurbs.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using Json = nlohmann::json;
using testing::CommandResult;
using testing::fresh_directory;
using testing::read_text;
using testing::run_dnurbs;

const std::string kCircle = std::string(DNURBS_TEST_DATA_DIR) + "/circle.json";

// What `dnurbs <arguments>` prints on stderr, expecting exit code 2 (bad command line).
std::string usage_error(const std::string& arguments) {
  const CommandResult result = run_dnurbs(arguments);
  EXPECT_EQ(result.exit_code, 2) << arguments;
  EXPECT_TRUE(result.out.empty()) << arguments;
  return result.err;
}

TEST(CommandLine, OutOfRangeAndMalformedIntegersNameTheOptionAndValue) {
  EXPECT_THAT(usage_error("eval " + kCircle + " --at 0.5 --derivatives 99"),
              HasSubstr("--derivatives: expected an integer in 0..15, got \"99\""));
  EXPECT_THAT(usage_error("run --resolution 2"),
              HasSubstr("--resolution: expected an integer in 3..1024, got \"2\""));
  EXPECT_THAT(usage_error("run --stop-after x"),
              HasSubstr("--stop-after: expected an integer in 0..100000000, got \"x\""));
  EXPECT_THAT(usage_error("import a.step b.json --index 9999999999"),
              HasSubstr("--index: expected an integer in 0..1073741824, got \"9999999999\""));
  EXPECT_THAT(usage_error("export " + kCircle + " out.obj --resolution 0x10"),
              HasSubstr("--resolution: expected an integer in 3..4096, got \"0x10\""));
  EXPECT_THAT(usage_error("fit surface points.xyz --degree 1.5"),
              HasSubstr("--degree: expected an integer in 1..9, got \"1.5\""));
  EXPECT_THAT(usage_error("serve --port 70000"),
              HasSubstr("--port: expected an integer in 0..65535, got \"70000\""));
  EXPECT_THAT(usage_error("design scene.json --max-evaluations 0"),
              HasSubstr("--max-evaluations: expected an integer in 1..100000000, got \"0\""));
}

TEST(CommandLine, NonFiniteAndOutOfRangeNumbersNameTheOptionAndValue) {
  const std::string to_obj = "export " + kCircle + " out.obj";
  EXPECT_THAT(usage_error("eval " + kCircle + " --at nan"),
              HasSubstr("--at nan: expected a finite number, got \"nan\""));
  EXPECT_THAT(usage_error("eval " + kCircle + " --at 0.5,x"),
              HasSubstr("--at 0.5,x: expected a finite number, got \"x\""));
  EXPECT_THAT(usage_error("fit surface points.xyz --smoothness 1e999"),
              HasSubstr("--smoothness: expected a finite number, got \"1e999\""));
  EXPECT_THAT(usage_error(to_obj + " --max-error nan"),
              HasSubstr("--max-error: expected a finite number > 0, got \"nan\""));
  EXPECT_THAT(usage_error(to_obj + " --max-error 0"),
              HasSubstr("--max-error: expected a finite number > 0, got \"0\""));
  EXPECT_THAT(usage_error(to_obj + " --radius -1"),
              HasSubstr("--radius: expected a finite number > 0, got \"-1\""));
  EXPECT_THAT(usage_error(to_obj + " --max-angle 200"),
              HasSubstr("--max-angle: expected a number in (0, 180], got \"200\""));
}

TEST(CommandLine, ValuesOutsideTheChoicesNameTheOptionAndValue) {
  EXPECT_THAT(usage_error("export " + kCircle + " out.obj --up-axis x"),
              HasSubstr("--up-axis: x not in {z,y}"));
  EXPECT_THAT(usage_error("fit cube points.xyz"),
              HasSubstr("SHAPE: cube not in {superquadric,surface}"));
  EXPECT_THAT(usage_error("design scene.json --algorithm newton"),
              HasSubstr("--algorithm: newton not in {slsqp,auglag_lbfgs}"));
}

TEST(CommandLine, UnknownOptionsAndExtraArgumentsAreNamed) {
  EXPECT_THAT(usage_error("info --bogus"), HasSubstr("not expected: --bogus"));
  EXPECT_THAT(usage_error("eval " + kCircle + " --at 0.5 --frobnicate"),
              HasSubstr("not expected: --frobnicate"));
  // make takes every recipe key as an option; another word is not one
  EXPECT_THAT(usage_error("make plane out.json --colour 1"), HasSubstr("--colour"));
  EXPECT_THAT(usage_error("run a.json b.json"), HasSubstr("not expected: b.json"));
  EXPECT_THAT(usage_error("preview a.obj b.png c.png"), HasSubstr("not expected: c.png"));
}

TEST(CommandLine, MissingValuesAndArgumentsAndRepeatedOptionsAreNamed) {
  EXPECT_THAT(usage_error("run --out"), HasSubstr("--out: 1 required TEXT missing"));
  EXPECT_THAT(usage_error("eval " + kCircle + " --at 0.5 --derivatives"),
              HasSubstr("--derivatives: 1 required"));
  EXPECT_THAT(usage_error("eval " + kCircle), HasSubstr("--at is required"));
  EXPECT_THAT(usage_error("eval --at 0.5"), HasSubstr("SHAPE is required"));
  EXPECT_THAT(usage_error("import part.step"), HasSubstr("OUT is required"));
  EXPECT_THAT(usage_error("design"), HasSubstr("SCENE is required"));
  EXPECT_THAT(usage_error("make plane out.json --size 1,1 --size 2,2"),
              HasSubstr("--size: At Most 1 required but received 2"));
  // The way back: the message ends with where to find the usage
  EXPECT_THAT(usage_error("run --out"), HasSubstr("run `dnurbs run --help` for usage"));
}

TEST(CommandLine, HelpListsEachSubcommandsOptions) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> options = {
      {"eval", {"--at U", "--derivatives N"}},
      {"run",
       {"--out DIR", "--resume CHECKPOINT", "--resolution N", "--stop-after N", "--no-preview",
        "--quiet"}},
      {"make", {"--control-points", "--major-radius", "--sections", "--split", "--translate"}},
      {"export",
       {"--resolution N", "--max-error E", "--max-angle DEG", "--compare", "--nurbs", "--radius R",
        "--up-axis z|y"}},
      {"import", {"--index K"}},
      {"fit",
       {"--out DIR", "--resolution N", "--quiet", "--degree P", "--spans N", "--smoothness S",
        "--iterations N"}},
      {"design", {"--out DIR", "--algorithm A", "--max-evaluations N", "--quiet"}},
      {"serve",
       {"--port N", "--host ADDR", "--out DIR", "--rate HZ", "--resolution N", "--web DIR"}}};
  for (const auto& [command, flags] : options) {
    for (const std::string help : {" --help", " -h"}) {
      const CommandResult result = run_dnurbs(command + help);
      EXPECT_EQ(result.exit_code, 0) << command << help;
      EXPECT_THAT(result.out, HasSubstr("usage: dnurbs " + command));
      for (const std::string& flag : flags) {
        EXPECT_THAT(result.out, HasSubstr(flag)) << command;
      }
    }
  }
}

TEST(CommandLine, HelpWinsOverABadCommandLine) {
  for (const std::string arguments :
       {"run --resolution 2 --help", "eval --bogus --help", "export --max-angle 200 -h",
        "fit cube points.xyz --help", "make --help plane", "import --index x --help"}) {
    const CommandResult result = run_dnurbs(arguments);
    EXPECT_EQ(result.exit_code, 0) << arguments << ": " << result.err;
    EXPECT_THAT(result.out, HasSubstr("usage: dnurbs ")) << arguments;
    EXPECT_TRUE(result.err.empty()) << arguments << ": " << result.err;
  }
}

// The number of vertices `dnurbs export` reports ("wrote F (N vertices, ...").
std::string reported_vertices(const std::string& arguments) {
  const CommandResult result = run_dnurbs(arguments);
  EXPECT_EQ(result.exit_code, 0) << arguments << ": " << result.err;
  const size_t open = result.out.find('(');
  return open == std::string::npos ? "" : result.out.substr(open, result.out.find(',') - open);
}

TEST(CommandLine, IntegersAreDecimalWithOrWithoutAnEqualsSign) {
  const auto folder = fresh_directory("command_line_integers");
  const std::string to_obj = "export " + kCircle + " " + (folder / "circle.obj").string();
  const std::string ten = reported_vertices(to_obj + " --resolution 10");
  EXPECT_EQ(ten, "(132 vertices");  // 11 rings of 12 around the tube
  EXPECT_EQ(reported_vertices(to_obj + " --resolution 010"), ten);  // not octal 8
  EXPECT_EQ(reported_vertices(to_obj + " --resolution +10"), ten);
  EXPECT_EQ(reported_vertices(to_obj + " --resolution=10"), ten);
  EXPECT_NE(reported_vertices(to_obj + " --resolution 8"), ten);
}

TEST(CommandLine, NegativeNumbersAreValuesNotOptions) {
  const auto folder = fresh_directory("command_line_negative_values");
  const std::string out = (folder / "rod.json").string();
  const CommandResult made = run_dnurbs("make line " + out + " --start -1,-2,0 --end -3,0,0");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const Json rod = Json::parse(read_text(out));
  EXPECT_EQ(rod["control_points"].front(), Json::parse("[-1, -2, 0]"));
  EXPECT_EQ(rod["control_points"].back(), Json::parse("[-3, 0, 0]"));
  const CommandResult at = run_dnurbs("eval " + kCircle + " --at -0.5");
  EXPECT_EQ(at.exit_code, 1);  // a value outside the domain, not an unknown option -0.5
  EXPECT_THAT(at.err, HasSubstr("--at -0.5"));
  EXPECT_THAT(at.err, Not(HasSubstr("not expected")));
}

}  // namespace
}  // namespace dnurbs
