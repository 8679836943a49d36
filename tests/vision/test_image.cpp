#include "dnurbs/vision/image.h"

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "../common/error_message.h"
#include "vision_test_images.h"

namespace dnurbs {
namespace {

using testing::error_message;
using testing::scratch_file;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// An image whose values are exact multiples of 1/maxval.
Image quantized_ramp(int width, int height, int maxval) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image(x, y) = static_cast<double>((37 * x + 101 * y) % (maxval + 1)) / maxval;
    }
  }
  return image;
}

TEST(ImageFiles, PngAndPgmRoundTripExactlyAt8And16Bits) {
  for (const int bits : {8, 16}) {
    const int maxval = bits == 8 ? 255 : 65535;
    const Image image = quantized_ramp(23, 17, maxval);
    const std::string png = scratch_file(std::to_string(bits) + ".png");
    const std::string pgm = scratch_file(std::to_string(bits) + ".pgm");
    write_png(image, png, bits);
    write_pgm(image, pgm, bits);
    for (const Image& back : {read_png(png), read_pgm(pgm), read_image(png), read_image(pgm)}) {
      ASSERT_EQ(back.width(), 23);
      ASSERT_EQ(back.height(), 17);
      // Values k / maxval survive quantization exactly; only the division rounds.
      EXPECT_LT((back.values - image.values).abs().maxCoeff(), 1e-15) << bits << " bits";
    }
  }
}

TEST(ImageFiles, WritersClampAndRound) {
  Image image(3, 1);
  image(0, 0) = -0.5;
  image(1, 0) = 0.5;
  image(2, 0) = 7.0;
  const std::string path = scratch_file("clamp.pgm");
  write_pgm(image, path);
  const Image back = read_pgm(path);
  EXPECT_EQ(back(0, 0), 0.0);
  EXPECT_EQ(back(1, 0), 128.0 / 255.0);  // 127.5 rounds away from zero
  EXPECT_EQ(back(2, 0), 1.0);
}

TEST(ImageFiles, AsciiPgmWithCommentsIsRead) {
  const std::string path = scratch_file("ascii.pgm");
  write_text(path, "P2\n# a comment\n3 2 # trailing comment\n10\n0 5 10\n\n1 2 3\n");
  const Image image = read_pgm(path);
  ASSERT_EQ(image.width(), 3);
  ASSERT_EQ(image.height(), 2);
  EXPECT_EQ(image(1, 0), 0.5);
  EXPECT_EQ(image(2, 0), 1.0);
  EXPECT_EQ(image(0, 1), 0.1);
  EXPECT_EQ(image(2, 1), 0.3);
}

TEST(ImageFiles, BadPgmFilesAreNamed) {
  const std::string path = scratch_file("bad.pgm");
  const auto message = [&](const std::string& text) {
    write_text(path, text);
    return error_message([&] { read_pgm(path); });
  };
  EXPECT_NE(message("P6\n1 1\n255\n").find("not P2 or P5"), std::string::npos);
  EXPECT_NE(message("P2\n2 2\n0\n").find("maxval 0"), std::string::npos);
  EXPECT_NE(message("P2\n2 2\n70000\n").find("maxval 70000"), std::string::npos);
  EXPECT_NE(message("P2\n2 1\n10\n3 11\n").find("sample 1 is 11, above maxval 10"),
            std::string::npos);
  EXPECT_NE(message("P5\n4 4\n255\nabc").find("data has 3 bytes, expected 16"), std::string::npos);
  EXPECT_NE(message("P5\n16000 16000\n65535\n").find("data has 0 bytes, expected 512000000"),
            std::string::npos);  // refused before allocating
  EXPECT_NE(message("P5\n100000 2\n255\n").find("100000 by 2"), std::string::npos);
  EXPECT_NE(message("P2\nx 2\n255\n").find("width is missing or not a number"), std::string::npos);
  EXPECT_NE(message("P2\n99999999999 2\n255\n").find("width is over"), std::string::npos);
  EXPECT_NE(message("").find(path), std::string::npos);  // names the file
}

TEST(ImageFiles, OtherBadInputIsNamed) {
  const std::string missing = scratch_file("missing.png");
  EXPECT_NE(error_message([&] { read_png(missing); }).find(missing), std::string::npos);
  EXPECT_NE(error_message([&] { read_image(missing); }).find("the image file does not exist"),
            std::string::npos);
  const std::string text = scratch_file("text.png");
  write_text(text, "hello world, not an image");
  EXPECT_NE(error_message([&] { read_image(text); }).find("neither PNG nor PGM"),
            std::string::npos);
  EXPECT_NE(error_message([&] { read_png(text); }).find(text), std::string::npos);
  Image image(2, 2);
  EXPECT_NE(
      error_message([&] { write_png(image, scratch_file("x.png"), 12); }).find("bit depth 12"),
      std::string::npos);
  image(1, 1) = std::nan("");
  EXPECT_NE(
      error_message([&] { write_pgm(image, scratch_file("x.pgm")); }).find("pixel (1, 1) is NaN"),
      std::string::npos);
  EXPECT_NE(error_message([] { Image(0, 3); }).find("0 by 3"), std::string::npos);
  EXPECT_NE(error_message([] { check_image_size(30000, 30000, "big"); }).find("exceed the limit"),
            std::string::npos);
}

}  // namespace
}  // namespace dnurbs
