#include "dnurbs/io/atomic_write.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "dnurbs/core/error.h"

namespace dnurbs {

std::filesystem::path temporary_sibling_path(const std::filesystem::path& target) {
  static std::atomic<unsigned long> counter{0};
  // Built by appends: GCC 12 warns falsely (-Wrestrict) about "." + std::string
  std::string name(1, '.');
  name.append(target.filename().string());
  name.append(".tmp-");
  name.append(std::to_string(static_cast<long>(::getpid())));
  name.append("-");
  name.append(std::to_string(counter.fetch_add(1)));
  return target.parent_path() / name;
}

int remove_stale_temporaries(const std::filesystem::path& directory) {
  int removed = 0;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    // ".<name>.tmp-<pid>-<counter>", a regular file (never a link or a folder)
    const std::string name = entry.path().filename().string();
    const auto tag = name.rfind(".tmp-");
    if (name.empty() || name.front() != '.' || tag == std::string::npos || tag == 0 ||
        !entry.is_regular_file(error) || entry.is_symlink(error)) {
      continue;
    }
    const std::string rest = name.substr(tag + 5);
    const auto dash = rest.find('-');
    const std::string pid = rest.substr(0, dash);
    const std::string count = dash == std::string::npos ? "" : rest.substr(dash + 1);
    const auto digits = [](const std::string& text) {
      return !text.empty() && text.size() <= 9 &&
             text.find_first_not_of("0123456789") == std::string::npos;
    };
    if (!digits(pid) || !digits(count)) {
      continue;
    }
    const auto process = static_cast<pid_t>(std::stol(pid));
    if (process > 0 && ::kill(process, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      removed += std::filesystem::remove(entry.path(), ignored) ? 1 : 0;
    }
  }
  return removed;
}

void write_file_atomically(const std::filesystem::path& target, const std::string& contents) {
  const std::filesystem::path temporary = temporary_sibling_path(target);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw make_error(target.string(),
                       ": cannot create a temporary file in its directory: ", std::strerror(errno));
    }
    out << contents;
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw make_error(target.string(), ": writing failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw make_error(target.string(),
                     ": cannot rename the temporary file to it: ", error.message());
  }
}

}  // namespace dnurbs
