#include "dnurbs/io/preview.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/surface/tessellation.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kToolsDir =
    std::filesystem::path(DNURBS_TEST_DATA_DIR) / ".." / ".." / "tools";

std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_preview_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

TEST(Preview, ScriptIsFoundInTheFirstDirectoryThatHasIt) {
  const std::filesystem::path script = find_preview_script({"/nonexistent", kToolsDir});
  EXPECT_EQ(script.filename(), "preview_mesh.py");
  EXPECT_TRUE(std::filesystem::is_regular_file(script));
  try {
    find_preview_script({"/nonexistent/a", "/nonexistent/b"});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("cannot find preview_mesh.py"));
    EXPECT_THAT(error.what(), HasSubstr("/nonexistent/a, /nonexistent/b"));
  }
}

TEST(Preview, MissingPythonIsReportedWithWhatToInstall) {
  try {
    find_python_with_matplotlib({"/nonexistent/python3", "false"});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("tried: /nonexistent/python3, false"));
    EXPECT_THAT(error.what(), HasSubstr("python3-matplotlib"));
  }
}

TEST(Preview, FailingRenderLeavesNoPng) {
  const auto directory = fresh_directory("failing");
  const auto script = find_preview_script({kToolsDir});
  { std::ofstream(directory / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 x\n"; }
  // `false` as the interpreter: the command fails whatever it is given
  EXPECT_THROW(render_preview("false", script, directory / "broken.obj", directory / "a.png"),
               Error);
  EXPECT_THROW(render_preview("false", script, directory / "none.obj", directory / "a.png"), Error);
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(directory)) {
    ++files;
  }
  EXPECT_EQ(files, 1);  // broken.obj only
  std::filesystem::remove_all(directory);
}

TEST(Preview, RendersAPngOfAnExportedMesh) {
  std::string python;
  try {
    python = find_python_with_matplotlib();
  } catch (const Error& error) {
    GTEST_SKIP() << error.what();
  }
  const auto directory = fresh_directory("render");
  export_mesh(tessellate_surface(periodic_torus(2.0, 0.5), 16, 8, "torus"),
              directory / "torus.obj");
  const auto script = find_preview_script({kToolsDir});
  render_preview(python, script, directory / "torus.obj", directory / "torus.png");
  std::ifstream in(directory / "torus.png", std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  EXPECT_GT(bytes.str().size(), 1000u);
  EXPECT_EQ(bytes.str().substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // A malformed face line makes the script fail with its message
  { std::ofstream(directory / "broken.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"; }
  try {
    render_preview(python, script, directory / "broken.obj", directory / "broken.png");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("broken.obj:4: cannot parse 'f 1 2 x'"));
  }
  EXPECT_FALSE(std::filesystem::exists(directory / "broken.png"));
  std::filesystem::remove_all(directory);
}

// The energies of a log over time: an 800 x 500 PNG; a log without the energy columns or with a
// bad value fails naming the line, and leaves no PNG
TEST(Preview, PlotsTheEnergiesOfALog) {
  std::string python;
  try {
    python = find_python_with_matplotlib();
  } catch (const Error& error) {
    GTEST_SKIP() << error.what();
  }
  const auto directory = fresh_directory("energy");
  const auto script = find_preview_script({"/nonexistent", kToolsDir}, kEnergyPlotScriptName);
  EXPECT_EQ(script.filename(), "plot_energy.py");
  {
    std::ofstream log(directory / "log.csv");
    log << "step,time,kinetic_energy,potential_energy,total_energy,probe_x\n";
    for (int step = 0; step <= 50; ++step) {
      const double t = 0.02 * step;
      log << step << "," << t << "," << std::sin(t) * std::sin(t) << ","
          << std::cos(t) * std::cos(t) << ",1,0\n";
    }
  }
  render_preview(python, script, directory / "log.csv", directory / "energy.png");
  std::ifstream in(directory / "energy.png", std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string png = bytes.str();
  ASSERT_GT(png.size(), 24U);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: width and height, big-endian, at bytes 16 and 20
  const auto big_endian = [&](size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(png[at])) << 24U) |
           (static_cast<unsigned>(static_cast<unsigned char>(png[at + 1])) << 16U) |
           (static_cast<unsigned>(static_cast<unsigned char>(png[at + 2])) << 8U) |
           static_cast<unsigned>(static_cast<unsigned char>(png[at + 3]));
  };
  EXPECT_EQ(big_endian(16), 800U);
  EXPECT_EQ(big_endian(20), 500U);
  { std::ofstream(directory / "short.csv") << "step,time,total_energy\n0,0,1\n"; }
  {
    std::ofstream(directory / "bad.csv")
        << "step,time,kinetic_energy,potential_energy,total_energy\n"
        << "0,0,1,2,3\n1,0.1,x,2,3\n";
  }
  for (const auto& [name, message] :
       {std::pair{"short.csv", "short.csv:1: no column kinetic_energy, potential_energy"},
        std::pair{"bad.csv", "bad.csv:3: cannot read the energies"}}) {
    try {
      render_preview(python, script, directory / name, directory / "x.png");
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr(message));
    }
  }
  EXPECT_FALSE(std::filesystem::exists(directory / "x.png"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
