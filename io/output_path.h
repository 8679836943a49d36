#pragma once
// Files written into an output folder under names that come from a scene or a client (model
// names): such a name must never reach outside the folder.

#include <filesystem>
#include <string>
#include <string_view>

namespace dnurbs {

/// True if `name` is a plain name: 1 to 100 characters from A-Z a-z 0-9 . _ -, not starting
/// with '.'. Scenes restrict the names of models, probes and outputs to these (they become file
/// names, CSV columns and names inside mesh files).
bool is_plain_name(std::string_view name);

/// What is_plain_name accepts, for messages.
inline constexpr const char* kPlainNameRule =
    "1 to 100 letters, digits, '_', '-' or '.', not starting with '.'";

/// `name` if it is a plain name (is_plain_name), otherwise `fallback`.
std::string output_file_stem(const std::string& name, const std::string& fallback);

/// directory / file_name, creating the directory if it is missing. Throws Error naming the
/// name if `file_name` is not a plain file name (a separator, "." or "..", empty) and naming
/// the directory if it cannot be created.
std::filesystem::path output_file_path(const std::filesystem::path& directory,
                                       const std::string& file_name);

}  // namespace dnurbs
