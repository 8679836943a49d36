#include "dnurbs/core/child_process_call.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <exception>
#include <new>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

constexpr char kResult = 'R';
constexpr char kFailure = 'E';

Error system_error(std::string_view what, const char* call) {
  return make_error(what, ": ", call, " failed: ", std::strerror(errno));
}

// The child's side: writes every byte or ends the child (the parent then sees a short reply).
void write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0 && errno == EINTR) {
      continue;
    }
    if (written <= 0) {
      ::_exit(3);
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

[[noreturn]] void run_child(const std::function<std::string()>& work, int fd, int cpu_seconds) {
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) {
    std::signal(signal, SIG_DFL);
  }
  // A crash writes no core file (into the working folder, outside any output folder)
  const rlimit no_core = {0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  // SIGXCPU at the limit, SIGKILL a second later if SIGXCPU is caught
  const rlimit cpu = {static_cast<rlim_t>(cpu_seconds), static_cast<rlim_t>(cpu_seconds) + 1};
  ::setrlimit(RLIMIT_CPU, &cpu);
  std::string reply;
  try {
    reply = kResult + work();
  } catch (const std::bad_alloc&) {
    reply = std::string(1, kFailure) + "out of memory";
  } catch (const std::exception& error) {
    reply = kFailure + std::string(error.what());
  }
  write_all(fd, reply.data(), reply.size());
  ::close(fd);
  ::_exit(0);
}

std::string read_until_end(int fd, std::string_view what) {
  std::string bytes;
  std::array<char, 1 << 16> buffer{};
  for (;;) {
    const ssize_t count = ::read(fd, buffer.data(), buffer.size());
    if (count < 0 && errno == EINTR) {
      continue;
    }
    if (count < 0) {
      throw system_error(what, "read from the child process");
    }
    if (count == 0) {
      return bytes;
    }
    bytes.append(buffer.data(), static_cast<std::size_t>(count));
  }
}

int wait_for(pid_t child, std::string_view what) {
  int status = 0;
  while (::waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) {
      throw system_error(what, "waitpid");
    }
  }
  return status;
}

}  // namespace

std::string call_in_child_process(const std::function<std::string()>& work, std::string_view what,
                                  int cpu_seconds) {
  if (cpu_seconds < 1) {
    throw make_error(what, ": the CPU time limit is ", cpu_seconds, " s, expected >= 1");
  }
  std::array<int, 2> pipe_ends{};
  if (::pipe2(pipe_ends.data(), O_CLOEXEC) != 0) {
    throw system_error(what, "pipe");
  }
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(pipe_ends[0]);
    ::close(pipe_ends[1]);
    throw system_error(what, "fork");
  }
  if (child == 0) {
    ::close(pipe_ends[0]);
    run_child(work, pipe_ends[1], cpu_seconds);
  }
  ::close(pipe_ends[1]);
  std::string reply;
  try {
    reply = read_until_end(pipe_ends[0], what);
  } catch (...) {
    ::close(pipe_ends[0]);
    wait_for(child, what);
    throw;
  }
  ::close(pipe_ends[0]);
  const int status = wait_for(child, what);
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGXCPU) {
      throw make_error(what, " did not finish within its ", cpu_seconds, " s of CPU time");
    }
    throw make_error(what, " crashed (signal ", signal, ", ", strsignal(signal), ")");
  }
  const int exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (exit_status != 0 || reply.empty() || (reply[0] != kResult && reply[0] != kFailure)) {
    throw make_error(what, " ended without a result (exit status ", exit_status, ")");
  }
  if (reply[0] == kFailure) {
    throw Error(reply.substr(1));
  }
  reply.erase(0, 1);
  return reply;
}

}  // namespace dnurbs
