#include "dnurbs/vision/volume.h"

#include <zlib.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../common/error_message.h"
#include "vision_test_images.h"

namespace dnurbs {
namespace {

using testing::error_message;
using testing::scratch_file;

void write_bytes(const std::string& path, const std::string& header, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  out << header;
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

std::string gzip(const std::string& data) {
  z_stream stream{};
  deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&stream, data.size()), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  stream.avail_in = static_cast<uInt>(data.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

TEST(NrrdFiles, DoubleVolumeRoundTripsExactly) {
  Volume volume(5, 4, 3);
  volume.spacing = Eigen::Vector3d(0.5, 0.25, 2.0 / 3.0);
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    volume.values[i] = std::sin(0.1 * static_cast<double>(i)) * 1e3;
  }
  const std::string path = scratch_file("round.nrrd");
  write_nrrd(volume, path);
  const Volume back = read_nrrd(path);
  EXPECT_EQ(back.size, volume.size);
  EXPECT_EQ(back.values, volume.values);  // raw doubles: bit for bit
  EXPECT_EQ(back.spacing, volume.spacing);
}

TEST(NrrdFiles, IntegerTypesEndiannessAsciiGzipAndDetachedDataAreRead) {
  const std::string path = scratch_file("typed.nrrd");
  const std::string header = "NRRD0004\n# comment\nkey:=value\ndimension: 3\nsizes: 2 1 2\n";
  // Big-endian signed 16-bit: 1, -2, 300, -32768.
  write_bytes(path, header + "type: short\nencoding: raw\nendian: big\n\n",
              std::string("\x00\x01\xff\xfe\x01\x2c\x80\x00", 8));
  EXPECT_EQ(read_nrrd(path).values, (std::vector<double>{1.0, -2.0, 300.0, -32768.0}));
  // Little-endian unsigned 32-bit, gzip-compressed.
  write_bytes(
      path, header + "type: uint32\nencoding: gzip\nendian: little\n\n",
      gzip(std::string("\x01\x00\x00\x00\x00\x00\x01\x00\xff\xff\xff\xff\x07\x00\x00\x00", 16)));
  EXPECT_EQ(read_nrrd(path).values, (std::vector<double>{1.0, 65536.0, 4294967295.0, 7.0}));
  // ASCII floats; uchar needs no endian.
  write_bytes(path, header + "type: float\nencoding: ascii\n\n", "0.5 1.5\n-2 3e2\n");
  EXPECT_EQ(read_nrrd(path).values, (std::vector<double>{0.5, 1.5, -2.0, 300.0}));
  // Detached data after a skipped line and two skipped bytes.
  const std::string data = scratch_file("typed.raw");
  write_bytes(data, "skip me\nXY", std::string("\x05\x06\x07\x08", 4));
  write_bytes(path,
              header + "type: uchar\nencoding: raw\ndata file: " +
                  std::filesystem::path(data).filename().string() +
                  "\nline skip: 1\nbyte skip: 2\n\n",
              "");
  EXPECT_EQ(read_nrrd(path).values, (std::vector<double>{5.0, 6.0, 7.0, 8.0}));
}

TEST(NrrdFiles, BadHeadersAreNamed) {
  const std::string path = scratch_file("bad.nrrd");
  const auto message = [&](const std::string& header, const std::string& data = "") {
    write_bytes(path, header, data);
    return error_message([&] { read_nrrd(path); });
  };
  const std::string base = "NRRD0004\ntype: uchar\nencoding: raw\n";
  EXPECT_NE(message("P5\n").find("is not NRRD0001..NRRD0005"), std::string::npos);
  // Any file may be named (a link to a secret one): its first line is not quoted, and header
  // lines are quoted only as short escaped excerpts
  EXPECT_EQ(message("root:*:20228:0:99999:7:::\n").find("root"), std::string::npos);
  EXPECT_NE(message("NRRD0004\nbad\x1b[2J line\n\n").find("header line \"bad\\x1b[2J line\""),
            std::string::npos);
  EXPECT_NE(message(base + "dimension: 2\nsizes: 2 2\n\n").find("dimension 2 is not 3"),
            std::string::npos);
  EXPECT_NE(message(base + "dimension: 3\n\n").find("\"sizes\" is missing"), std::string::npos);
  EXPECT_NE(message(base + "dimension: 3\nsizes: 2 2 x\n\n").find("not 3 integers"),
            std::string::npos);
  EXPECT_NE(message(base + "dimension: 3\nsizes: 5000 2 2\n\n").find("5000 by 2 by 2"),
            std::string::npos);
  EXPECT_NE(message("NRRD0004\ntype: quad\nencoding: raw\ndimension: 3\nsizes: 1 1 1\n\n")
                .find("type \"quad\""),
            std::string::npos);
  EXPECT_NE(message("NRRD0004\ntype: uchar\nencoding: bzip2\ndimension: 3\nsizes: 1 1 1\n\n", "x")
                .find("encoding \"bzip2\""),
            std::string::npos);
  EXPECT_NE(message(base + "dimension: 3\nsizes: 2 2 2\n\n", "abc")
                .find("raw data holds 3 samples, expected 8"),
            std::string::npos);
  EXPECT_NE(message("NRRD0004\ntype: short\nencoding: raw\ndimension: 3\nsizes: 1 1 1\n\n", "ab")
                .find("\"endian\" is missing"),
            std::string::npos);
  EXPECT_NE(message(base + "dimension: 3\nsizes: 1 1 1\nspacings: 1 0 1\n\n", "a")
                .find("not 3 positive numbers"),
            std::string::npos);
  EXPECT_NE(
      message(base + "dimension: 3\nsizes: 1 1 1\nbyte skip: -5\n\n", "a").find("byte skip -5"),
      std::string::npos);
  EXPECT_NE(message(base + "dimension: 3\nsizes: 1 1 1\nno colon here\n\n").find("no \": \""),
            std::string::npos);
  // A compressed payload may be small and declare many samples (a gzip bomb): over 2^28 samples
  // are refused by count, below that by the memory budget before anything is decoded (16 bytes
  // a sample: 512^3 need 2147 MB, over a limit of 1 GB)
  EXPECT_NE(message("NRRD0004\ntype: uchar\nencoding: gzip\ndimension: 3\n"
                    "sizes: 4096 4096 4096\n\n",
                    "x")
                .find("68719476736 voxels exceed the limit"),
            std::string::npos);
  ::setenv("DNURBS_MEMORY_LIMIT", "1e9", 1);
  EXPECT_NE(message("NRRD0004\ntype: uchar\nencoding: gzip\ndimension: 3\n"
                    "sizes: 512 512 512\n\n",
                    "x")
                .find("(512 x 512 x 512 samples) needs about 2147 MB, more than the 1000 MB"),
            std::string::npos);
  ::unsetenv("DNURBS_MEMORY_LIMIT");
}

TEST(VolumeSlices, StackOfPgmSlicesIsRead) {
  std::vector<std::string> paths;
  for (int z = 0; z < 3; ++z) {
    Image slice(4, 2);
    slice.values.setConstant(z / 255.0);
    slice(1, 1) = 1.0;
    paths.push_back(scratch_file("slice" + std::to_string(z) + ".pgm"));
    write_pgm(slice, paths.back());
  }
  const Volume volume = read_volume_slices(paths);
  EXPECT_EQ(volume.size, (std::array<int, 3>{4, 2, 3}));
  EXPECT_EQ(volume(0, 0, 2), 2.0 / 255.0);
  EXPECT_EQ(volume(1, 1, 1), 1.0);
  write_pgm(Image(5, 2), paths[1]);
  EXPECT_NE(error_message([&] {
              read_volume_slices(paths);
            }).find("is 5 by 2, the first slice is 4 by 2"),
            std::string::npos);
  EXPECT_NE(error_message([] { read_volume_slices({}); }).find("empty"), std::string::npos);
}

}  // namespace
}  // namespace dnurbs
