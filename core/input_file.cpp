#include "dnurbs/core/input_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include "dnurbs/core/error.h"

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

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

std::string printable_excerpt(std::string_view text, std::size_t max_bytes) {
  std::string result;
  for (std::size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      result += '\\';
      result += static_cast<char>(c);
    } else if (c >= 0x20 && c < 0x7f) {
      result += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", static_cast<unsigned>(c));
      result += escaped;
    }
  }
  if (text.size() > max_bytes) {
    result += "...";
  }
  return result;
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
