// Atomic writes leave no temporary behind, and the temporaries of a killed run are removed by the
// next run in the same folder (io/atomic_write.h).

#include "dnurbs/io/atomic_write.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/common/child_process.h"

namespace dnurbs {
namespace {

std::filesystem::path fresh_directory() {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_atomic_write_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

TEST(AtomicWrite, WritesTheFileAndNoTemporary) {
  const auto directory = fresh_directory();
  write_file_atomically(directory / "a.json", "{}\n");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    EXPECT_EQ(entry.path().filename(), "a.json");
    ++files;
  }
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(directory);
}

// A full disk, injected as a file size limit (RLIMIT_FSIZE, SIGXFSZ ignored) in a child: the
// write fails with an Error naming the file and the previous file stays
TEST(AtomicWrite, AWriteThatFailsKeepsThePreviousFile) {
  const auto directory = fresh_directory();
  const auto target = directory / "log.csv";
  { std::ofstream(target) << "previous\n"; }
  const int code = testing::exit_code_with_file_size_limit(4096, [&] {
    try {
      write_file_atomically(target, std::string(100000, 'x'));
    } catch (const Error& error) {
      return std::string(error.what()).find(target.string() + ": writing failed") == 0 ? 0 : 2;
    }
    return 1;
  });
  EXPECT_EQ(code, 0) << "1: no error, 2: a message without the file";
  std::ifstream in(target);
  std::string contents((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(contents, "previous\n");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    EXPECT_EQ(entry.path().filename(), "log.csv");
    ++files;
  }
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(directory);
}

TEST(AtomicWrite, StaleTemporariesOfEndedProcessesAreRemovedAndNothingElse) {
  const auto directory = fresh_directory();
  const std::string dead = std::to_string(testing::ended_process_id());
  const std::string alive = std::to_string(::getpid());
  const auto touch = [&](const std::string& name) { std::ofstream(directory / name) << "x"; };
  touch(".log.csv.tmp-" + dead + "-0");     // a killed run's: removed
  touch(".sheet.obj.tmp-" + dead + "-17");  // removed
  touch(".log.csv.tmp-" + alive + "-3");    // a running process's (this one): kept
  touch("log.csv");                         // ordinary files: kept
  touch("notes.tmp-" + dead + "-0");        // not hidden: not ours, kept
  touch(".x.tmp-" + dead);                  // no counter: not ours, kept
  touch(".x.tmp-12ab-0");                   // not a process id: kept
  std::filesystem::create_directory(directory / (".d.tmp-" + dead + "-1"));  // a folder: kept
  EXPECT_EQ(remove_stale_temporaries(directory), 2);
  EXPECT_FALSE(std::filesystem::exists(directory / (".log.csv.tmp-" + dead + "-0")));
  EXPECT_FALSE(std::filesystem::exists(directory / (".sheet.obj.tmp-" + dead + "-17")));
  for (const std::string& kept :
       {".log.csv.tmp-" + alive + "-3", std::string("log.csv"), "notes.tmp-" + dead + "-0",
        ".x.tmp-" + dead, std::string(".x.tmp-12ab-0"), ".d.tmp-" + dead + "-1"}) {
    EXPECT_TRUE(std::filesystem::exists(directory / kept)) << kept;
  }
  EXPECT_EQ(remove_stale_temporaries(directory), 0);
  EXPECT_EQ(remove_stale_temporaries(directory / "missing"), 0);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace dnurbs
