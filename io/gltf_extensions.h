#pragma once
// glTF documents as assimp writes them list extensions they never use (KHR_materials_volume,
// FB_ngon_encoding) in "extensionsUsed"; the glTF 2.0 specification (section 3.12) lists there
// the extensions the document uses. This keeps only those.

#include <filesystem>

#include <nlohmann/json.hpp>

namespace dnurbs {

/// Removes from "extensionsUsed" and "extensionsRequired" every name that no "extensions"
/// object of the document uses (and the arrays when they become empty).
void drop_unused_gltf_extensions(nlohmann::json& document);

/// The same on a file in place: a .gltf JSON document, or the JSON chunk of a binary .glb (the
/// chunk padded with spaces to 4 bytes and the lengths of the header updated, glTF 2.0 section
/// 4.4). Throws Error naming the file if it cannot be read or written, or is not glTF.
void drop_unused_gltf_extensions(const std::filesystem::path& file, bool binary);

}  // namespace dnurbs
