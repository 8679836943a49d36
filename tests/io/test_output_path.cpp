// Names from scenes and clients never leave the output folder.

#include "dnurbs/io/output_path.h"

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

TEST(OutputPath, KeepsPlainStemsAndReplacesTheRest) {
  EXPECT_EQ(output_file_stem("hat", "model0"), "hat");
  EXPECT_EQ(output_file_stem("sheet_2.v-1", "model0"), "sheet_2.v-1");
  for (const char* hostile :
       {"", "../x", "a/b", ".hidden", "..", "a\\b", "x y", "\xc3\xa9", "name\n"}) {
    EXPECT_EQ(output_file_stem(hostile, "model3"), "model3") << hostile;
  }
  EXPECT_EQ(output_file_stem(std::string(101, 'a'), "m"), "m");
}

TEST(OutputPath, RefusesNamesOutsideTheFolderAndCreatesIt) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "dnurbs_output_path";
  std::filesystem::remove_all(folder);
  EXPECT_EQ(output_file_path(folder, "hat.obj"), folder / "hat.obj");
  EXPECT_TRUE(std::filesystem::is_directory(folder));
  for (const char* bad : {"", ".", "..", "../hat.obj", "/etc/passwd", "a\\b.obj"}) {
    EXPECT_THROW(output_file_path(folder, bad), Error) << bad;
  }
}

}  // namespace
}  // namespace dnurbs
