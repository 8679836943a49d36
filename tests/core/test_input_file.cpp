// Input files are read within bounds: regular files only, checked before they are opened (a
// FIFO would block, /dev/zero never ends), and of a bounded size.

#include "dnurbs/core/input_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

std::string refusal(const std::filesystem::path& path, std::uintmax_t limit = kInputFileLimit) {
  try {
    read_input_file(path, "scene file", limit);
  } catch (const Error& error) {
    return error.what();
  }
  return "read";
}

TEST(InputFile, ReadsARegularFileAndFollowsLinks) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_input_file_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const std::string contents(200000, 'x');  // several read buffers
  { std::ofstream(directory / "a.json") << contents << "end"; }
  EXPECT_EQ(read_input_file(directory / "a.json", "scene file"), contents + "end");
  std::filesystem::create_symlink(directory / "a.json", directory / "link.json");
  EXPECT_EQ(read_input_file(directory / "link.json", "scene file"), contents + "end");
  { std::ofstream(directory / "empty.json"); }
  EXPECT_EQ(read_input_file(directory / "empty.json", "scene file"), "");
  std::filesystem::remove_all(directory);
}

TEST(InputFile, RefusesWhatIsNotABoundedRegularFile) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_input_file_bad_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  EXPECT_EQ(refusal(directory / "none.json"),
            (directory / "none.json").string() + ": the scene file does not exist");
  EXPECT_THAT(refusal(directory), HasSubstr(": the scene file is not a regular file"));
  // A FIFO with no writer: opening it would block forever; it is refused without opening
  ASSERT_EQ(::mkfifo((directory / "fifo").c_str(), 0600), 0);
  EXPECT_EQ(refusal(directory / "fifo"),
            (directory / "fifo").string() +
                ": the scene file is not a regular file (a folder, a FIFO, a device or a socket)");
  EXPECT_THAT(refusal("/dev/zero"), HasSubstr("/dev/zero: the scene file is not a regular file"));
  std::filesystem::create_symlink("/dev/zero", directory / "zero.json");
  EXPECT_THAT(refusal(directory / "zero.json"), HasSubstr("is not a regular file"));
  { std::ofstream(directory / "big.json") << std::string(1001, 'x'); }
  EXPECT_EQ(refusal(directory / "big.json", 1000),
            (directory / "big.json").string() +
                ": the scene file holds 1001 bytes, more than the limit of 1000");
  EXPECT_EQ(refusal(directory / "big.json", 1001), "read");
  EXPECT_THROW(check_input_file(directory / "big.json", "mesh file", 10), Error);
  std::filesystem::remove_all(directory);
}

TEST(InputFile, ExcerptsAreShortPrintableAndEscaped) {
  EXPECT_EQ(printable_excerpt("plain text"), "plain text");
  EXPECT_EQ(printable_excerpt("a\"b\\c"), "a\\\"b\\\\c");
  EXPECT_EQ(printable_excerpt(std::string("line\nbreak\0nul\x1b[2J\xc3\xa9", 20)),
            "line\\x0abreak\\x00nul\\x1b[2J\\xc3\\xa9");
  EXPECT_EQ(printable_excerpt(std::string(50, 'x')), std::string(40, 'x') + "...");
  EXPECT_EQ(printable_excerpt("abcdef", 3), "abc...");
  EXPECT_EQ(printable_excerpt(""), "");
}

}  // namespace
}  // namespace dnurbs
