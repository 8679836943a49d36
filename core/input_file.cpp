#include "core/input_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace dnurbs {

void check_input_file(const std::filesystem::path& path, std::string_view what,
                      std::uintmax_t limit) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw make_error(path.string(), ": the ", what, " does not exist");
  }
  if (error) {
    throw make_error(path.string(), ": cannot read the ", what, ": ", error.message());
  }
  if (status.type() != std::filesystem::file_type::regular) {
    throw make_error(path.string(), ": the ", what,
                     " is not a regular file (a folder, a FIFO, a device or a socket)");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) {
    throw make_error(path.string(), ": cannot read the ", what, ": ", error.message());
  }
  if (size > limit) {
    throw make_error(path.string(), ": the ", what, " holds ", size,
                     " bytes, more than the limit of ", limit);
  }
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::uintmax_t limit) {
  check_input_file(path, what, limit);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw make_error(path.string(), ": cannot read the ", what, ": ", std::strerror(errno));
  }
  std::string contents;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof(buffer));
    contents.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (contents.size() > limit) {
      throw make_error(path.string(), ": the ", what, " grew beyond the limit of ", limit,
                       " bytes while it was read");
    }
  }
  if (in.bad()) {
    throw make_error(path.string(), ": cannot read the ", what, ": reading failed");
  }
  return contents;
}

}  // namespace dnurbs
