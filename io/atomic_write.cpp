#include "io/atomic_write.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/error.h"

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
