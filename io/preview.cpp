#include "dnurbs/io/preview.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <system_error>

#include "dnurbs/core/error.h"
#include "dnurbs/io/atomic_write.h"

namespace dnurbs {
namespace {

// The argument in single quotes for /bin/sh (a quote inside becomes '\'')
std::string shell_quote(const std::string& argument) {
  std::string quoted = "'";
  for (const char c : argument) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    throw make_error("cannot start \"", command, "\"");
  }
  std::array<char, 4096> buffer{};
  size_t read = 0;
  while ((read = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), read);
  }
  const int status = ::pclose(pipe);
  result.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace

std::filesystem::path find_preview_script(const std::vector<std::filesystem::path>& directories,
                                          const char* name) {
  std::string searched;
  for (const auto& directory : directories) {
    std::filesystem::path script = directory / name;
    std::error_code error;
    if (std::filesystem::is_regular_file(script, error)) {
      return script;
    }
    searched += (searched.empty() ? "" : ", ") + directory.string();
  }
  throw make_error("cannot find ", name, " (searched: ", searched, ")");
}

std::string find_python_with_matplotlib(const std::vector<std::string>& candidates) {
  std::string tried;
  for (const auto& python : candidates) {
    if (python.empty()) {
      continue;
    }
    const CommandResult probe = run_command(shell_quote(python) + " -c 'import matplotlib'");
    if (probe.exit_code == 0) {
      return python;
    }
    tried += (tried.empty() ? "" : ", ") + python;
  }
  throw make_error("no python with matplotlib found (tried: ", tried,
                   "); install python3-matplotlib to render previews");
}

void render_preview(const std::string& python, const std::filesystem::path& script,
                    const std::filesystem::path& mesh, const std::filesystem::path& png) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(mesh, error)) {
    throw make_error(mesh.string(), ": the mesh file does not exist");
  }
  const std::filesystem::path temporary = temporary_sibling_path(png);
  const CommandResult result =
      run_command(shell_quote(python) + " " + shell_quote(script.string()) + " " +
                  shell_quote(mesh.string()) + " " + shell_quote(temporary.string()));
  if (result.exit_code != 0 || !std::filesystem::is_regular_file(temporary, error)) {
    std::filesystem::remove(temporary, error);
    throw make_error(png.string(), ": the preview script failed (exit code ", result.exit_code, ")",
                     result.output.empty() ? std::string() : ":\n" + result.output);
  }
  std::filesystem::rename(temporary, png, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw make_error(png.string(), ": cannot rename the rendered preview to it");
  }
}

}  // namespace dnurbs
