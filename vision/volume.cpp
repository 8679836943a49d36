#include "dnurbs/vision/volume.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/core/memory_budget.h"
#include "dnurbs/vision/image.h"

namespace dnurbs {

namespace {

/// The NRRD sample types read_nrrd accepts: their byte count and whether signed / floating.
struct SampleType {
  int bytes = 1;
  bool is_signed = false;
  bool is_float = false;
};

SampleType parse_sample_type(const std::string& type, const std::string& path) {
  static const std::map<std::string, SampleType> sample_types = {
      {"uchar", {1, false, false}},
      {"unsigned char", {1, false, false}},
      {"uint8", {1, false, false}},
      {"uint8_t", {1, false, false}},
      {"signed char", {1, true, false}},
      {"int8", {1, true, false}},
      {"int8_t", {1, true, false}},
      {"ushort", {2, false, false}},
      {"unsigned short", {2, false, false}},
      {"uint16", {2, false, false}},
      {"uint16_t", {2, false, false}},
      {"short", {2, true, false}},
      {"signed short", {2, true, false}},
      {"int16", {2, true, false}},
      {"int16_t", {2, true, false}},
      {"uint", {4, false, false}},
      {"unsigned int", {4, false, false}},
      {"uint32", {4, false, false}},
      {"uint32_t", {4, false, false}},
      {"int", {4, true, false}},
      {"signed int", {4, true, false}},
      {"int32", {4, true, false}},
      {"int32_t", {4, true, false}},
      {"float", {4, true, true}},
      {"double", {8, true, true}}};
  const auto found = sample_types.find(type);
  if (found == sample_types.end()) {
    throw make_error("NRRD file ", path, ": type \"", printable_excerpt(type),
                     "\" is not supported");
  }
  return found->second;
}

/// Decodes one sample of `type` from `bytes` stored with the given endianness.
double decode_sample(const unsigned char* bytes, const SampleType& type, bool big_endian) {
  std::array<unsigned char, 8> ordered{};
  for (int i = 0; i < type.bytes; ++i) {
    const bool swap = big_endian == (std::endian::native == std::endian::little);
    ordered[static_cast<std::size_t>(i)] = bytes[swap ? type.bytes - 1 - i : i];
  }
  if (type.is_float) {
    if (type.bytes == 4) {
      float value = 0.0F;
      std::memcpy(&value, ordered.data(), 4);
      return value;
    }
    double value = 0.0;
    std::memcpy(&value, ordered.data(), 8);
    return value;
  }
  std::uint64_t raw = 0;
  std::memcpy(&raw, ordered.data(), static_cast<std::size_t>(type.bytes));
  if (type.is_signed) {
    const int shift = 64 - 8 * type.bytes;
    return static_cast<double>(static_cast<std::int64_t>(raw << shift) >> shift);
  }
  return static_cast<double>(raw);
}

/// Inflates gzip data (zlib with the gzip wrapper) to exactly `expected` bytes.
std::string gunzip(const std::string& compressed, std::size_t expected, const std::string& path) {
  std::string out(expected, '\0');
  z_stream stream{};
  if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) {
    throw make_error("NRRD file ", path, ": zlib cannot start inflating");
  }
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  const int status = inflate(&stream, Z_FINISH);
  const std::size_t produced = expected - stream.avail_out;
  inflateEnd(&stream);
  if (produced != expected || (status != Z_STREAM_END && status != Z_BUF_ERROR)) {
    throw make_error("NRRD file ", path, ": gzip data gives ", produced, " bytes, expected ",
                     expected);
  }
  return out;
}

/// The fields of a NRRD header that read_nrrd uses (keys lower-cased as the format defines
/// them), and the stream positioned at the first data byte when the data is attached.
std::map<std::string, std::string> read_nrrd_header(std::istream& in, const std::string& path) {
  std::string line;
  std::getline(in, line);
  if (line.rfind("NRRD000", 0) != 0 || line.size() != 8 || line[7] < '1' || line[7] > '5') {
    // Nothing of the file is quoted: it may be any file (a link to a secret one)
    throw make_error("NRRD file ", path, ": the first line is not NRRD0001..NRRD0005");
  }
  std::map<std::string, std::string> fields;
  int count = 0;
  while (std::getline(in, line) && !line.empty() && line != "\r") {
    if (++count > 10000) {
      throw make_error("NRRD file ", path, ": header has over 10000 lines");
    }
    if (line[0] == '#' || line.find(":=") != std::string::npos) {
      continue;  // comments and key/value pairs carry no geometry
    }
    const auto colon = line.find(": ");
    if (colon == std::string::npos) {
      throw make_error("NRRD file ", path, ": header line \"", printable_excerpt(line),
                       "\" has no \": \"");
    }
    std::string value = line.substr(colon + 2);
    while (!value.empty() && (value.back() == '\r' || value.back() == ' ')) {
      value.pop_back();
    }
    fields[line.substr(0, colon)] = value;
  }
  return fields;
}

const std::string& required_field(const std::map<std::string, std::string>& fields,
                                  const std::string& key, const std::string& path) {
  const auto found = fields.find(key);
  if (found == fields.end()) {
    throw make_error("NRRD file ", path, ": required field \"", key, "\" is missing");
  }
  return found->second;
}

/// Sizes and spacings of a 3-D NRRD header. raw_samples is how many samples the payload holds,
/// checked against the sizes before allocating when the encoding is raw.
Volume allocate_nrrd_volume(const std::map<std::string, std::string>& fields,
                            const std::string& path, std::size_t raw_samples) {
  if (required_field(fields, "dimension", path) != "3") {
    throw make_error("NRRD file ", path, ": dimension ", printable_excerpt(fields.at("dimension")),
                     " is not 3");
  }
  std::istringstream sizes(required_field(fields, "sizes", path));
  std::array<long long, 3> n{0, 0, 0};
  if (!(sizes >> n[0] >> n[1] >> n[2])) {
    throw make_error("NRRD file ", path, ": sizes \"", printable_excerpt(fields.at("sizes")),
                     "\" are not 3 integers");
  }
  check_volume_size(n[0], n[1], n[2], "NRRD file " + path);
  const auto samples = static_cast<std::size_t>(n[0] * n[1] * n[2]);
  if (required_field(fields, "encoding", path) == "raw" && raw_samples < samples) {
    throw make_error("NRRD file ", path, ": raw data holds ", raw_samples, " samples, expected ",
                     samples);
  }
  // The volume in double and the decoded payload (a gzip-encoded payload of a few MB can
  // declare 4096^3 samples): at most 16 bytes a sample
  check_memory_budget(16.0 * static_cast<double>(samples),
                      "NRRD file " + path + " (" + std::to_string(n[0]) + " x " +
                          std::to_string(n[1]) + " x " + std::to_string(n[2]) + " samples)",
                      "its sizes");
  Volume volume(static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]));
  if (const auto found = fields.find("spacings"); found != fields.end()) {
    std::istringstream spacings(found->second);
    for (int axis = 0; axis < 3; ++axis) {
      double h = 1.0;
      if (!(spacings >> h) || !(h > 0.0)) {
        throw make_error("NRRD file ", path, ": spacings \"", printable_excerpt(found->second),
                         "\" are not 3 positive numbers");
      }
      volume.spacing[axis] = h;
    }
  }
  return volume;
}

/// The data bytes after `line skip` lines and `byte skip` bytes, attached or detached.
std::string read_nrrd_payload(std::istream& header_stream,
                              const std::map<std::string, std::string>& fields,
                              const std::string& path) {
  std::ifstream detached;
  std::istream* in = &header_stream;
  if (const auto found = fields.find("data file"); found != fields.end()) {
    const auto data_path = std::filesystem::path(path).parent_path() / found->second;
    check_input_file(data_path, "NRRD data file");
    detached.open(data_path, std::ios::binary);
    if (!detached) {
      throw make_error("NRRD file ", path, ": data file ", data_path.string(), " cannot be opened");
    }
    in = &detached;
  }
  const auto skip = [&](const char* key) {
    const auto found = fields.find(key);
    long long value = 0;
    if (found != fields.end()) {
      std::istringstream text(found->second);
      if (!(text >> value)) {
        throw make_error("NRRD file ", path, ": ", key, " \"", printable_excerpt(found->second),
                         "\" is not an integer");
      }
    }
    if (value < 0 || value > (1LL << 30)) {
      throw make_error("NRRD file ", path, ": ", key, " ", value, " is not in [0, 2^30]");
    }
    return value;
  };
  std::string line;
  for (long long i = skip("line skip"); i > 0; --i) {
    std::getline(*in, line);
  }
  in->ignore(skip("byte skip"));
  return {std::istreambuf_iterator<char>(*in), std::istreambuf_iterator<char>()};
}

}  // namespace

void check_volume_size(long long nx, long long ny, long long nz, const std::string& what) {
  for (const long long n : {nx, ny, nz}) {
    if (n < 1 || n > kMaxVolumeSide) {
      throw make_error(what, ": size ", nx, " by ", ny, " by ", nz, " is outside [1, ",
                       kMaxVolumeSide, "] per side");
    }
  }
  if (nx * ny * nz > kMaxVolumeVoxels) {
    throw make_error(what, ": ", nx * ny * nz, " voxels exceed the limit of ", kMaxVolumeVoxels);
  }
}

Volume::Volume(int nx, int ny, int nz, double fill) : size{nx, ny, nz} {
  check_volume_size(nx, ny, nz, "volume");
  values.assign(static_cast<std::size_t>(nx) * ny * nz, fill);
}

Volume read_volume_slices(const std::vector<std::string>& paths) {
  if (paths.empty()) {
    throw make_error("volume slice list is empty");
  }
  const Image first = read_image(paths.front());
  check_volume_size(first.width(), first.height(), static_cast<long long>(paths.size()),
                    "slice stack starting with " + paths.front());
  Volume volume(first.width(), first.height(), static_cast<int>(paths.size()));
  for (std::size_t z = 0; z < paths.size(); ++z) {
    const Image slice = z == 0 ? first : read_image(paths[z]);
    if (slice.width() != first.width() || slice.height() != first.height()) {
      throw make_error("slice ", paths[z], " is ", slice.width(), " by ", slice.height(),
                       ", the first slice is ", first.width(), " by ", first.height());
    }
    for (int y = 0; y < slice.height(); ++y) {
      for (int x = 0; x < slice.width(); ++x) {
        volume(x, y, static_cast<int>(z)) = slice(x, y);
      }
    }
  }
  return volume;
}

Volume read_nrrd(const std::string& path) {
  check_input_file(path, "NRRD file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw make_error("NRRD file ", path, " cannot be opened");
  }
  const auto fields = read_nrrd_header(in, path);
  const SampleType type = parse_sample_type(required_field(fields, "type", path), path);
  const std::string& encoding = required_field(fields, "encoding", path);
  std::string payload = read_nrrd_payload(in, fields, path);
  Volume volume =
      allocate_nrrd_volume(fields, path, encoding == "raw" ? payload.size() / type.bytes : 0);
  const std::size_t count = volume.values.size();
  if (encoding == "ascii" || encoding == "text" || encoding == "txt") {
    std::istringstream text(payload);
    for (std::size_t i = 0; i < count; ++i) {
      if (!(text >> volume.values[i])) {
        throw make_error("NRRD file ", path, ": ASCII data ends after ", i, " of ", count,
                         " samples");
      }
    }
    return volume;
  }
  const std::size_t bytes = count * static_cast<std::size_t>(type.bytes);
  if (encoding == "gzip" || encoding == "gz") {
    payload = gunzip(payload, bytes, path);
  } else if (encoding != "raw") {
    throw make_error("NRRD file ", path, ": encoding \"", printable_excerpt(encoding),
                     "\" is not supported");
  }
  if (payload.size() < bytes) {
    throw make_error("NRRD file ", path, ": raw data has ", payload.size(), " bytes, expected ",
                     bytes);
  }
  bool big_endian = false;
  if (type.bytes > 1) {
    const std::string& endian = required_field(fields, "endian", path);
    if (endian != "little" && endian != "big") {
      throw make_error("NRRD file ", path, ": endian \"", printable_excerpt(endian),
                       "\" is not little or big");
    }
    big_endian = endian == "big";
  }
  const auto* data = reinterpret_cast<const unsigned char*>(payload.data());
  for (std::size_t i = 0; i < count; ++i) {
    volume.values[i] =
        decode_sample(data + i * static_cast<std::size_t>(type.bytes), type, big_endian);
  }
  return volume;
}

void write_nrrd(const Volume& volume, const std::string& path) {
  check_volume_size(volume.size[0], volume.size[1], volume.size[2], "volume for " + path);
  std::ofstream out(path, std::ios::binary);
  out.precision(17);
  out << "NRRD0004\n# written by dnurbs\ntype: double\ndimension: 3\nsizes: " << volume.size[0]
      << ' ' << volume.size[1] << ' ' << volume.size[2] << "\nspacings: " << volume.spacing[0]
      << ' ' << volume.spacing[1] << ' ' << volume.spacing[2]
      << "\nencoding: raw\nendian: little\n\n";
  for (const double value : volume.values) {
    std::array<unsigned char, 8> bytes{};
    std::memcpy(bytes.data(), &value, 8);
    if constexpr (std::endian::native == std::endian::big) {
      std::reverse(bytes.begin(), bytes.end());
    }
    out.write(reinterpret_cast<const char*>(bytes.data()), 8);
  }
  if (!out) {
    throw make_error("NRRD file ", path, " cannot be written");
  }
}

}  // namespace dnurbs
