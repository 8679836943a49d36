#pragma once
// Writing files atomically: write a temporary file beside the target, then rename it over the
// target, so that readers never see a half-written file.

#include <filesystem>
#include <string>

namespace dnurbs {

/// A fresh path in the same directory as `target` for a temporary file that will be renamed to
/// it: ".<name>.tmp-<process id>-<counter>". The file is not created.
std::filesystem::path temporary_sibling_path(const std::filesystem::path& target);

/// Removes the temporary files (temporary_sibling_path) in `directory` left by processes that no
/// longer run (a killed run): those whose process id is not alive. Files of running processes,
/// this one included, and every other file are kept. Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& directory);

/// Writes `contents` to `target` through a temporary sibling file and std::filesystem::rename.
/// Throws Error naming the file if writing or renaming fails (no temporary file is left).
void write_file_atomically(const std::filesystem::path& target, const std::string& contents);

}  // namespace dnurbs
