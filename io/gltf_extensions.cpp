#include "dnurbs/io/gltf_extensions.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Every key of every "extensions" object in the document.
void collect_used(const nlohmann::json& value, std::set<std::string>& used) {
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      if (key == "extensions" && child.is_object()) {
        for (const auto& entry : child.items()) {
          used.insert(entry.key());
        }
      }
      collect_used(child, used);
    }
  } else if (value.is_array()) {
    for (const auto& child : value) {
      collect_used(child, used);
    }
  }
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw make_error(file.string(), ": cannot read the glTF file");
  }
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    throw make_error(file.string(), ": cannot write the glTF file");
  }
}

std::uint32_t read_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof(value));  // glTF is little-endian, as x86 and ARM
  return value;
}

void write_u32(std::string& bytes, std::size_t at, std::uint32_t value) {
  std::memcpy(bytes.data() + at, &value, sizeof(value));
}

constexpr std::size_t kHeaderBytes = 12;          // magic, version, length
constexpr std::size_t kChunkHeaderBytes = 8;      // length, type
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"

}  // namespace

void drop_unused_gltf_extensions(nlohmann::json& document) {
  std::set<std::string> used;
  collect_used(document, used);
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!document.contains(list) || !document[list].is_array()) {
      continue;
    }
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& name : document[list]) {
      if (name.is_string() && used.contains(name.get<std::string>())) {
        kept.push_back(name);
      }
    }
    if (kept.empty()) {
      document.erase(list);
    } else {
      document[list] = kept;
    }
  }
}

void drop_unused_gltf_extensions(const std::filesystem::path& file, bool binary) {
  std::string bytes = read_bytes(file);
  if (!binary) {
    nlohmann::json document = nlohmann::json::parse(bytes, nullptr, false);
    if (document.is_discarded() || !document.is_object()) {
      throw make_error(file.string(), ": not a glTF JSON document");
    }
    drop_unused_gltf_extensions(document);
    write_bytes(file, document.dump(2) + "\n");
    return;
  }
  if (bytes.size() < kHeaderBytes + kChunkHeaderBytes || bytes.compare(0, 4, "glTF") != 0 ||
      read_u32(bytes, kHeaderBytes + 4) != kJsonChunk) {
    throw make_error(file.string(), ": not a binary glTF file with a JSON chunk");
  }
  const std::size_t json_length = read_u32(bytes, kHeaderBytes);
  const std::size_t json_start = kHeaderBytes + kChunkHeaderBytes;
  if (json_length > bytes.size() - json_start) {
    throw make_error(file.string(), ": its JSON chunk of ", json_length,
                     " bytes runs past the end of the file");
  }
  nlohmann::json document =
      nlohmann::json::parse(bytes.substr(json_start, json_length), nullptr, false);
  if (document.is_discarded() || !document.is_object()) {
    throw make_error(file.string(), ": its JSON chunk is not a glTF document");
  }
  drop_unused_gltf_extensions(document);
  std::string json = document.dump();
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string rebuilt = bytes.substr(0, json_start);
  rebuilt += json;
  rebuilt += bytes.substr(json_start + json_length);
  write_u32(rebuilt, kHeaderBytes, static_cast<std::uint32_t>(json.size()));
  write_u32(rebuilt, 8, static_cast<std::uint32_t>(rebuilt.size()));
  write_bytes(file, rebuilt);
}

}  // namespace dnurbs
