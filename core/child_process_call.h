#pragma once
// Running a function in a child process, so that a crash inside it (a third-party parser's
// SIGSEGV on a malformed file) becomes an Error of the caller instead of the end of the
// program. dnurbs reads mesh files through assimp this way (io/mesh_import.h): libFuzzer found
// inputs on which Debian 12's assimp 5.2.5 reads past its buffers and dies.

#include <functional>
#include <string>
#include <string_view>

namespace dnurbs {

/// Forks; the child runs `work`, with at most `cpu_seconds` of CPU time, and sends back the bytes
/// it returns (or the message of an exception it throws), then ends with _exit, so no destructor or
/// atexit handler of the parent's state runs twice. Returns the bytes. Throws Error:
///  - the child's exception message, as is, when `work` threw;
///  - "<what> crashed (signal 11, Segmentation fault)" when a signal ended the child (SIGSEGV,
///    SIGBUS, SIGFPE, SIGILL and SIGABRT have their default action in the child, so a sanitizer
///    or a crash handler of the parent does not report the child's crash as its own, and the
///    child writes no core file);
///  - "<what> did not finish within its N s of CPU time" (a parser in an endless loop: the
///    child ends by SIGXCPU; SIGKILL, a second later, is reported as a crash, as is the
///    out-of-memory killer's);
///  - "<what> ended without a result (exit status N)" when it exited early;
///  - naming the system call when pipe, fork or waitpid fails.
/// After a fork of a multithreaded process the child may only rely on what fork keeps
/// consistent: glibc's malloc, stdio and the C++ runtime are (glibc's fork handlers take and
/// reset their locks); `work` must not wait for another thread of the parent.
std::string call_in_child_process(const std::function<std::string()>& work, std::string_view what,
                                  int cpu_seconds);

}  // namespace dnurbs
