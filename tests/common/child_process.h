#pragma once
// Child processes for tests of what happens to files when writes fail or a run is killed:
// a full disk injected as a file size limit, and the id of a process that has ended.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstddef>

namespace dnurbs::testing {

/// Runs `body` (returning an exit code 0..255) in a forked child whose files cannot grow past
/// `bytes` (RLIMIT_FSIZE: a write beyond it fails with EFBIG, as on a full disk; SIGXFSZ is
/// ignored so that the write returns the error). Returns the child's exit code, or -1 if it did
/// not exit normally.
template <typename Body>
int exit_code_with_file_size_limit(std::size_t bytes, Body body) {
  const pid_t child = ::fork();
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{bytes, bytes};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    ::_exit(body());
  }
  int status = 0;
  if (child < 0 || ::waitpid(child, &status, 0) != child || !WIFEXITED(status)) {
    return -1;
  }
  return WEXITSTATUS(status);
}

/// The id of a process that has ended: a child that exits at once, reaped.
inline pid_t ended_process_id() {
  const pid_t child = ::fork();
  if (child == 0) {
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

}  // namespace dnurbs::testing
