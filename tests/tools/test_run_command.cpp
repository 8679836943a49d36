// Runs the built `dnurbs run` and `dnurbs info`: the default demo, every example scene, a run
// stopped part-way and resumed, a diverging scene, malformed scenes, help and progress output.

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/tools/run_dnurbs.h"

#include "dnurbs/io/checkpoint.h"
#include "dnurbs/io/mesh_import.h"
#include "dnurbs/io/shape_file.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = DNURBS_TEST_DATA_DIR;
const std::filesystem::path kExamples = kData / ".." / ".." / "examples" / "scenes";

using Result = testing::CommandResult;
using testing::fresh_directory;
using testing::kDnurbs;
using testing::read_text;

Result run(const std::string& arguments) {
  return testing::run_dnurbs(arguments);
}

double max_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() ? (a - b).lpNorm<Eigen::Infinity>()
                              : std::numeric_limits<double>::infinity();
}

TEST(RunCommand, DefaultDemoWritesFramesLogFinalMeshPreviewAndShapes) {
  const auto directory = fresh_directory("demo");
  const auto start = std::chrono::steady_clock::now();
  const Result result = run("run --out " + directory.string() + " --resolution 6");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(result.exit_code, 0) << result.err;
  RecordProperty("demo_seconds", std::to_string(seconds));
  // Not a terminal: plain progress lines, one per 10 %, with the rate, the time left, the
  // simulated time and the energy (log.csv's total_energy at that step, to the 6 digits printed)
  std::smatch line;
  ASSERT_TRUE(std::regex_search(result.out, line,
                                std::regex("\nstep 100/200 \\(50%\\), [0-9.e+]+ steps/s, [^;]+ "
                                           "left; t = ([0-9.e+-]+), energy ([0-9.e+-]+)\n")))
      << result.out;
  EXPECT_EQ(std::stod(line[1]), 1.0);  // dt 0.01
  EXPECT_EQ(result.out.find('\r'), std::string::npos);
  for (const char* file :
       {"log.csv", "checkpoint.json", "demo.obj", "demo.mtl", "demo.png", "hat.json", "torus.json",
        "frames/demo_000000.obj", "frames/demo_000200.obj"}) {
    EXPECT_TRUE(std::filesystem::exists(directory / file)) << file;
  }
  // The final mesh holds the sculpted hat (6 x 6 cells), the torus (6 x 3 cells, periodic) and
  // the superquadric pendulum's link and bob (6 x 6 cells each)
  const std::vector<TriangleMesh> meshes = import_meshes(directory / "demo.obj");
  ASSERT_EQ(meshes.size(), 4u);
  EXPECT_EQ(meshes[0].name, "hat");
  EXPECT_EQ(meshes[0].triangle_count(), 2 * 6 * 6);
  EXPECT_EQ(meshes[1].name, "torus");
  EXPECT_EQ(meshes[1].triangle_count(), 2 * 6 * 3);
  // Superquadrics: 6 x 6 cells with a fan of 6 triangles at each pole (one vertex per pole)
  EXPECT_EQ(meshes[2].name, "link");
  EXPECT_EQ(meshes[2].triangle_count(), 2 * 6 * 4 + 2 * 6);
  EXPECT_EQ(meshes[3].name, "bob");
  EXPECT_EQ(meshes[3].triangle_count(), 2 * 6 * 4 + 2 * 6);
  // The springs raised the crown: the highest vertex of the hat is well above the flat sheet
  EXPECT_GT(meshes[0].vertices.col(2).maxCoeff(), 0.5);
  // The log has the initial row and one per step, with the probe columns
  const std::string log = read_text(directory / "log.csv");
  EXPECT_THAT(log, ::testing::StartsWith("step,time,kinetic_energy,potential_energy,"
                                         "total_energy,max_violation,violation_0,violation_1,"
                                         "crown_x"));
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1 + 201);
  std::istringstream rows(log);
  std::string row;
  for (int i = 0; i <= 101; ++i) {  // the header, the initial state, then step 1 to 100
    std::getline(rows, row);
  }
  ASSERT_TRUE(row.starts_with("100,"));
  std::istringstream fields(row);
  std::string field;
  for (int i = 0; i < 5; ++i) {  // step, time, kinetic_energy, potential_energy, total_energy
    std::getline(fields, field, ',');
  }
  EXPECT_NEAR(std::stod(line[2]), std::stod(field), 1e-5 * std::abs(std::stod(field)));
  EXPECT_EQ(read_checkpoint_file(directory / "checkpoint.json").step, 200);
  EXPECT_TRUE(std::holds_alternative<NurbsSurface>(read_shape_file(directory / "hat.json")));
  const std::string png = read_text(directory / "demo.png");
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::filesystem::remove_all(directory);
}

TEST(RunCommand, EveryExampleSceneRuns) {
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".json") {
      continue;
    }
    const std::string name = entry.path().stem().string();
    const auto directory = fresh_directory("example_" + name);
    const Result result = run("run " + entry.path().string() + " --out " + directory.string() +
                              " --resolution 4 --no-preview");
    EXPECT_FALSE(result.signalled) << name;
    if (name == "diverging_sheet") {
      // Diverges on purpose: exit 1, a message, the last good state written
      EXPECT_EQ(result.exit_code, 1) << name;
      EXPECT_THAT(result.err, HasSubstr("diverged"));
      EXPECT_THAT(result.err, HasSubstr("the last good state (step "));
      EXPECT_TRUE(std::filesystem::exists(directory / "checkpoint.json"));
      EXPECT_TRUE(std::filesystem::exists(directory / "sheet.obj"));
    } else {
      EXPECT_EQ(result.exit_code, 0) << name << ": " << result.err;
      EXPECT_TRUE(std::filesystem::exists(directory / "log.csv")) << name;
      EXPECT_TRUE(std::filesystem::exists(directory / "checkpoint.json")) << name;
    }
    std::filesystem::remove_all(directory);
  }
}

TEST(RunCommand, RunStoppedPartWayAndResumedEndsLikeAnUninterruptedRun) {
  // The snake example with a checkpoint every 30 steps (outputs do not change the state hash)
  std::string scene = read_text(kExamples / "snake_contour.json");
  const std::string key = "\"output\": {";
  scene.replace(scene.find(key), key.size(), key + "\"checkpoint_every\": 30, ");
  const auto directory = fresh_directory("resume");
  const auto scene_path = directory / "snake.json";
  std::ofstream(scene_path) << scene;
  const Result whole =
      run("run " + scene_path.string() + " --out " + (directory / "whole").string() + " --quiet");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.out, "");  // --quiet: nothing but errors
  EXPECT_EQ(whole.err, "");
  const Result stopped = run("run " + scene_path.string() + " --out " +
                             (directory / "parts").string() + " --stop-after 100");
  ASSERT_EQ(stopped.exit_code, 0) << stopped.err;
  EXPECT_THAT(stopped.out, HasSubstr("stopped after step 100"));
  EXPECT_EQ(read_checkpoint_file(directory / "parts" / "checkpoint.json").step, 90);
  const Result resumed =
      run("run " + scene_path.string() + " --out " + (directory / "parts").string() + " --resume " +
          (directory / "parts" / "checkpoint.json").string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.out, HasSubstr("resuming from"));
  const Checkpoint a = read_checkpoint_file(directory / "whole" / "checkpoint.json");
  const Checkpoint b = read_checkpoint_file(directory / "parts" / "checkpoint.json");
  EXPECT_EQ(b.step, 200);
  EXPECT_EQ(a.time, b.time);
  // Same operations on the same bits: 0 in practice; 1e-12 is the promised bound
  EXPECT_LE(max_difference(a.coordinates, b.coordinates), 1e-12);
  EXPECT_LE(max_difference(a.velocities, b.velocities), 1e-12);
  EXPECT_EQ(read_text(directory / "parts" / "log.csv"), read_text(directory / "whole" / "log.csv"));
  // A checkpoint of another scene is refused
  const Result wrong = run("run " + (kExamples / "curve_sculpting.json").string() + " --out " +
                           (directory / "wrong").string() + " --resume " +
                           (directory / "parts" / "checkpoint.json").string());
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_THAT(wrong.err, HasSubstr("scene_hash: expected"));
  std::filesystem::remove_all(directory);
}

// A real kill (SIGKILL part-way through a run that writes a mesh every step): every file under
// its final name is complete, and resuming from the last checkpoint ends like an uninterrupted run
TEST(RunCommand, KilledRunLeavesCompleteFilesAndResumes) {
  const std::string demo = read_text(kExamples / "hat_demo.json");
  const auto directory = fresh_directory("killed");
  const auto with_output = [&](const std::string& output) {
    std::string scene = demo;
    const auto begin = scene.find("\"output\": {");
    const auto end = scene.find('}', begin);
    scene.replace(begin, end - begin + 1, "\"output\": {" + output + "}");
    return scene;
  };
  // The state hash ignores "output", so both files describe the same run
  std::ofstream(directory / "slow.json")
      << with_output(R"("name": "demo", "mesh_every": 1, "resolution": 40, "checkpoint_every": 5)");
  std::ofstream(directory / "fast.json") << with_output(R"("name": "demo", "resolution": 4)");
  const std::string killed = (directory / "killed").string();
  const int status =
      std::system(("timeout -s KILL 1.5 " + kDnurbs + " run " + (directory / "slow.json").string() +
                   " --out " + killed + " >/dev/null 2>&1")
                      .c_str());
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    std::filesystem::remove_all(directory);
    GTEST_SKIP() << "the run finished before it could be killed";
  }
  // Every mesh and the log under their final names are complete
  int frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory / "killed" / "frames")) {
    if (entry.path().extension() == ".obj") {
      EXPECT_EQ(import_meshes(entry.path()).size(), 4u) << entry.path();
      ++frames;
    }
  }
  RecordProperty("frames_before_kill", frames);
  const std::string log = read_text(directory / "killed" / "log.csv");
  EXPECT_TRUE(log.empty() || log.back() == '\n');
  if (!std::filesystem::exists(directory / "killed" / "checkpoint.json")) {
    std::filesystem::remove_all(directory);
    GTEST_SKIP() << "killed before the first checkpoint";
  }
  const Checkpoint at_kill = read_checkpoint_file(directory / "killed" / "checkpoint.json");
  EXPECT_EQ(at_kill.step % 5, 0);
  const Result resumed = run("run " + (directory / "fast.json").string() + " --out " + killed +
                             " --no-preview --resume " + killed + "/checkpoint.json");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const Result whole = run("run " + (directory / "fast.json").string() + " --no-preview --out " +
                           (directory / "whole").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const Checkpoint a = read_checkpoint_file(directory / "whole" / "checkpoint.json");
  const Checkpoint b = read_checkpoint_file(directory / "killed" / "checkpoint.json");
  EXPECT_EQ(b.step, 200);
  // Same operations on the same bits: 0 in practice; 1e-12 is the promised bound
  EXPECT_LE(max_difference(a.coordinates, b.coordinates), 1e-12);
  EXPECT_LE(max_difference(a.velocities, b.velocities), 1e-12);
  std::filesystem::remove_all(directory);
}

TEST(RunCommand, MalformedScenesExitOneNamingFileAndJsonPath) {
  // The whole corpus of tests/data/bad_scenes through the binary (the io tests check the
  // messages in process too): exit 1, never a signal, the file and the expected substrings
  const auto directory = fresh_directory("bad");
  std::ifstream manifest(kData / "bad_scenes" / "expected_messages.tsv");
  ASSERT_TRUE(manifest);
  std::string line;
  int count = 0;
  while (std::getline(manifest, line)) {
    if (line.empty() || line[0] == '#') {
      continue;
    }
    std::vector<std::string> fields;
    std::istringstream parts(line);
    std::string field;
    while (std::getline(parts, field, '\t')) {
      fields.push_back(field);
    }
    ASSERT_GE(fields.size(), 2u) << line;
    const auto path = kData / "bad_scenes" / fields[0];
    const Result result = run("run " + path.string() + " --out " + directory.string());
    EXPECT_FALSE(result.signalled) << fields[0];
    EXPECT_EQ(result.exit_code, 1) << fields[0];
    EXPECT_THAT(result.err, HasSubstr("error: " + path.string() + ": ")) << fields[0];
    for (size_t k = 1; k < fields.size(); ++k) {
      EXPECT_THAT(result.err, HasSubstr(fields[k])) << fields[0];
    }
    ++count;
  }
  EXPECT_GE(count, 30);
  const Result info = run("info " + (kData / "bad_scenes" / "zero_dt.json").string());
  EXPECT_EQ(info.exit_code, 1);
  EXPECT_THAT(info.err, HasSubstr("integrator.dt: expected a number > 0"));
  const Result missing = run("run " + (kData / "no_such.json").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err, HasSubstr("no_such.json: the scene file does not exist"));
  EXPECT_EQ(run("run --resolution 2").exit_code, 2);
  EXPECT_EQ(run("run a.json b.json").exit_code, 2);
  EXPECT_EQ(run("info --bogus").exit_code, 2);
  std::filesystem::remove_all(directory);
}

TEST(InfoCommand, DescribesModelsMatricesAndCost) {
  const Result demo = run("info");
  ASSERT_EQ(demo.exit_code, 0) << demo.err;
  EXPECT_THAT(demo.out, HasSubstr("hat (dnurbs_surface): 147 coordinates"));
  EXPECT_THAT(demo.out, HasSubstr("constant (assembled and factored once)"));
  EXPECT_THAT(demo.out, HasSubstr("S (x) I_3"));
  EXPECT_THAT(demo.out, HasSubstr("LDL^T factor"));
  EXPECT_THAT(demo.out, HasSubstr("estimated cost per step"));
  // The built-in demo is examples/scenes/hat_demo.json: the same state hash
  const Result example = run("info " + (kExamples / "hat_demo.json").string());
  ASSERT_EQ(example.exit_code, 0) << example.err;
  const auto hash = [](const std::string& text) {
    const auto at = text.find("state hash: ");
    return at == std::string::npos ? std::string() : text.substr(at + 12, 16);
  };
  EXPECT_EQ(hash(example.out), hash(demo.out));
  EXPECT_FALSE(hash(demo.out).empty());
  const Result cloth = run("info " + (kExamples / "cloth_terzopoulos.json").string());
  ASSERT_EQ(cloth.exit_code, 0) << cloth.err;
  EXPECT_THAT(cloth.out, HasSubstr("state-dependent (assembled and factored every step)"));
}

TEST(RunCommand, HelpDescribesRunAndInfo) {
  const Result run_help = run("run --help");
  EXPECT_EQ(run_help.exit_code, 0);
  EXPECT_THAT(run_help.out, HasSubstr("usage: dnurbs run [SCENE.json]"));
  EXPECT_THAT(run_help.out, HasSubstr("--resume CHECKPOINT"));
  const Result info_help = run("info --help");
  EXPECT_EQ(info_help.exit_code, 0);
  EXPECT_THAT(info_help.out, HasSubstr("usage: dnurbs info"));
  EXPECT_THAT(run("--help").out, HasSubstr("info [SCENE.json]"));
}

// One run writes its final meshes in every listed format, and the preview renders the first
// (here glTF binary, which the preview script cannot read: it goes through a temporary OBJ)
TEST(RunCommand, OneRunWritesEveryListedFormatAndPreviewsTheFirst) {
  const auto directory = fresh_directory("formats");
  std::ofstream(directory / "sheet.json") << R"({
    "models": [{"name": "sheet", "type": "dnurbs_surface",
                "make": {"kind": "plane", "size": [3, 3]},
                "material": {"damping_density": 2, "a10": 1, "a01": 1},
                "boundary": {"clamp_border": true}}],
    "forces": [{"type": "spring", "model": "sheet", "at": [1.5, 1.5], "stiffness": 50,
                "target": [1.5, 1.5, 0.5]}],
    "run": {"steps": 5},
    "output": {"name": "sheet", "format": ["glb", "obj", "stl"], "resolution": 8,
               "preview": true, "mesh_every": 5}})";
  const auto out = directory / "out";
  const Result result =
      run("run " + (directory / "sheet.json").string() + " --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const std::string format : {"glb", "obj", "stl"}) {
    const std::vector<TriangleMesh> meshes = import_meshes(out / ("sheet." + format));
    ASSERT_EQ(meshes.size(), 1U) << format;
    EXPECT_EQ(meshes[0].triangle_count(), 2 * 8 * 8) << format;
    EXPECT_THAT(result.out, HasSubstr("sheet." + format + " (final state)"));
  }
  // The same final surface in every file: every OBJ vertex is a glTF vertex (the OBJ writer
  // orders them by first use; glTF stores single precision, glTF's Y-up undone on import)
  const Eigen::MatrixX3d obj = import_meshes(out / "sheet.obj")[0].vertices;
  const Eigen::MatrixX3d glb = import_meshes(out / "sheet.glb")[0].vertices;
  ASSERT_EQ(obj.rows(), glb.rows());
  double farthest = 0.0;
  for (Eigen::Index r = 0; r < obj.rows(); ++r) {
    farthest = std::max(farthest, (glb.rowwise() - obj.row(r)).rowwise().norm().minCoeff());
  }
  EXPECT_LT(farthest, 1e-6);
  EXPECT_GT(obj.col(2).maxCoeff(), 0.01);  // lifted by the spring
  // Frames in the first format only
  EXPECT_TRUE(std::filesystem::exists(out / "frames" / "sheet_000005.glb"));
  EXPECT_FALSE(std::filesystem::exists(out / "frames" / "sheet_000005.obj"));
  const std::string png = read_text(out / "sheet.png");
  ASSERT_GT(png.size(), 1000U);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // dnurbs preview reads any mesh format too
  const Result preview =
      run("preview " + (out / "sheet.stl").string() + " " + (directory / "stl.png").string());
  ASSERT_EQ(preview.exit_code, 0) << preview.err;
  EXPECT_EQ(read_text(directory / "stl.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
