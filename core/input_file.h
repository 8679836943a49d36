#pragma once
// Reading input files (scenes, shapes, checkpoints, point sets, meshes, images and volumes)
// within bounds: only regular files (links followed), of a bounded size, checked before they
// are opened, so that a FIFO blocks nothing, a device such as /dev/zero is not read without end
// and a folder gets a message rather than a failed parse.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace dnurbs {

/// The largest input file dnurbs reads: 1 GiB (a 1000 x 1000 control-point shape file is about
/// 60 MB).
inline constexpr std::uintmax_t kInputFileLimit = std::uintmax_t{1} << 30;

/// Throws Error unless `path` names a regular file (after links) of at most `limit` bytes:
/// "<path>: the <what> does not exist", "<path>: the <what> is not a regular file (a folder, a
/// FIFO, a device or a socket)", "<path>: the <what> holds N bytes, more than the limit of L".
/// `what` names the kind of file ("scene file").
void check_input_file(const std::filesystem::path& path, std::string_view what,
                      std::uintmax_t limit = kInputFileLimit);

/// A short excerpt of text from an input file for a message: at most `max_bytes` bytes, '"' and
/// '\\' escaped with a backslash, anything outside printable ASCII as \xNN, "..." appended when
/// cut; so that a message can neither carry line breaks or terminal controls nor much of a file.
std::string printable_excerpt(std::string_view text, std::size_t max_bytes = 40);

/// The path's extension in lower case, with its dot (".gltf" for "Part.GLTF"), which decides
/// how a file is read or written.
std::string lowercase_extension(const std::filesystem::path& path);

/// check_input_file, then the whole file's bytes (at most `limit`, even if it grows meanwhile).
/// Throws Error "<path>: cannot read the <what>: <reason>" if opening or reading fails.
std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::uintmax_t limit = kInputFileLimit);

}  // namespace dnurbs
