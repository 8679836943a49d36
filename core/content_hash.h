#pragma once
// A short fingerprint of bytes: FNV-1a 64 (Fowler, Noll and Vo), as 16 hex digits. It tells
// whether two inputs are the same (scene state hashes, the data files a scene read); it is not
// a cryptographic hash.

#include <string>
#include <string_view>

namespace dnurbs {

/// FNV-1a 64 of `bytes`, as 16 lower-case hex digits.
std::string content_hash(std::string_view bytes);

}  // namespace dnurbs
