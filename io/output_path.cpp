#include "dnurbs/io/output_path.h"

#include <algorithm>
#include <system_error>

#include "dnurbs/core/error.h"

namespace dnurbs {

bool is_plain_name(std::string_view name) {
  const auto plain = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  };
  return !name.empty() && name.size() <= 100 && name.front() != '.' &&
         std::all_of(name.begin(), name.end(), plain);
}

std::string output_file_stem(const std::string& name, const std::string& fallback) {
  return is_plain_name(name) ? name : fallback;
}

std::filesystem::path output_file_path(const std::filesystem::path& directory,
                                       const std::string& file_name) {
  const std::filesystem::path name(file_name);
  if (file_name.empty() || file_name == "." || file_name == ".." ||
      file_name.find_first_of("/\\") != std::string::npos || name.has_root_path()) {
    throw make_error("output file name \"", file_name,
                     "\" is not a plain file name inside the output folder");
  }
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw make_error("cannot create the output folder ", directory.string(), ": ", error.message());
  }
  return directory / name;
}

}  // namespace dnurbs
