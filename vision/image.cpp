#include "dnurbs/vision/image.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"

namespace dnurbs {

namespace {

/// Reads one whitespace-separated unsigned integer of a PGM header or P2 body, skipping '#'
/// comments to the end of their line.
long long read_pgm_integer(std::istream& in, const std::string& path, const char* what) {
  int c = in.get();
  while (in && (std::isspace(c) != 0 || c == '#')) {
    if (c == '#') {
      while (in && c != '\n') {
        c = in.get();
      }
    }
    c = in.get();
  }
  if (!in || std::isdigit(c) == 0) {
    throw make_error("PGM file ", path, ": ", what, " is missing or not a number");
  }
  long long value = 0;
  while (in && std::isdigit(c) != 0) {
    value = value * 10 + (c - '0');
    if (value > std::numeric_limits<int>::max()) {
      throw make_error("PGM file ", path, ": ", what, " is over ", std::numeric_limits<int>::max());
    }
    c = in.get();
  }
  return value;
}

/// Clamps to [0, 1] and scales to [0, maxval]; throws for NaN.
std::uint16_t quantize(double value, int maxval, const std::string& path, int x, int y) {
  if (std::isnan(value)) {
    throw make_error("image for ", path, ": pixel (", x, ", ", y, ") is NaN");
  }
  return static_cast<std::uint16_t>(std::lround(std::clamp(value, 0.0, 1.0) * maxval));
}

void check_bit_depth(int bit_depth, const std::string& path) {
  if (bit_depth != 8 && bit_depth != 16) {
    throw make_error("image file ", path, ": bit depth ", bit_depth, " is not 8 or 16");
  }
}

}  // namespace

void check_image_size(long long width, long long height, const std::string& what) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide) {
    throw make_error(what, ": size ", width, " by ", height, " is outside [1, ", kMaxImageSide,
                     "] per side");
  }
  if (width * height > kMaxImagePixels) {
    throw make_error(what, ": ", width * height, " pixels exceed the limit of ", kMaxImagePixels);
  }
}

Image::Image(int width, int height, double fill) {
  check_image_size(width, height, "image");
  values.setConstant(width, height, fill);
}

Image read_png(const std::string& path) {
  // libpng's simplified API reports errors through png_image::message instead of longjmp.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&png, path.c_str()) == 0) {
    throw make_error("PNG file ", path, ": ", png.message);
  }
  try {
    check_image_size(png.width, png.height, "PNG file " + path);
  } catch (...) {
    png_image_free(&png);
    throw;
  }
  // 16-bit files are read as 16-bit linear grey, 8-bit files as 8-bit grey: both without any
  // gamma conversion for greyscale input, so write_png / read_png round-trip exactly.
  const bool sixteen_bit = (png.format & PNG_FORMAT_FLAG_LINEAR) != 0;
  png.format = sixteen_bit ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
  const std::size_t count = static_cast<std::size_t>(png.width) * png.height;
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  if (sixteen_bit) {
    std::vector<std::uint16_t> buffer(count);
    if (png_image_finish_read(&png, nullptr, buffer.data(), 0, nullptr) == 0) {
      throw make_error("PNG file ", path, ": ", png.message);
    }
    for (std::size_t i = 0; i < count; ++i) {
      image.values(static_cast<Eigen::Index>(i)) = buffer[i] / 65535.0;
    }
  } else {
    std::vector<std::uint8_t> buffer(count);
    if (png_image_finish_read(&png, nullptr, buffer.data(), 0, nullptr) == 0) {
      throw make_error("PNG file ", path, ": ", png.message);
    }
    for (std::size_t i = 0; i < count; ++i) {
      image.values(static_cast<Eigen::Index>(i)) = buffer[i] / 255.0;
    }
  }
  return image;
}

Image read_pgm(const std::string& path) {
  check_input_file(path, "PGM file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw make_error("PGM file ", path, " cannot be opened");
  }
  std::array<char, 2> magic{};
  in.read(magic.data(), 2);
  if (!in || magic[0] != 'P' || (magic[1] != '2' && magic[1] != '5')) {
    throw make_error("PGM file ", path, ": magic number is not P2 or P5");
  }
  const bool ascii = magic[1] == '2';
  const long long width = read_pgm_integer(in, path, "width");
  const long long height = read_pgm_integer(in, path, "height");
  check_image_size(width, height, "PGM file " + path);
  const long long maxval = read_pgm_integer(in, path, "maxval");
  if (maxval < 1 || maxval > 65535) {
    throw make_error("PGM file ", path, ": maxval ", maxval, " is outside [1, 65535]");
  }
  // read_pgm_integer consumed the single whitespace byte that ends the header.
  const int bytes = maxval > 255 ? 2 : 1;
  if (!ascii) {
    // Check the data is all there before allocating for it.
    const auto here = in.tellg();
    in.seekg(0, std::ios::end);
    const long long available = static_cast<long long>(in.tellg() - here);
    in.seekg(here);
    if (available < width * height * bytes) {
      throw make_error("PGM file ", path, ": data has ", available, " bytes, expected ",
                       width * height * bytes);
    }
  }
  Image image(static_cast<int>(width), static_cast<int>(height));
  for (long long i = 0; i < width * height; ++i) {
    long long sample = 0;
    if (ascii) {
      sample = read_pgm_integer(in, path, "sample");
    } else {
      std::array<unsigned char, 2> raw{};
      in.read(reinterpret_cast<char*>(raw.data()), bytes);
      if (!in) {
        throw make_error("PGM file ", path, ": data ends after ", i, " of ", width * height,
                         " samples");
      }
      sample = bytes == 2 ? (raw[0] << 8) | raw[1] : raw[0];  // big-endian, Netpbm's order
    }
    if (sample > maxval) {
      throw make_error("PGM file ", path, ": sample ", i, " is ", sample, ", above maxval ",
                       maxval);
    }
    image.values(static_cast<Eigen::Index>(i)) = static_cast<double>(sample) / maxval;
  }
  return image;
}

Image read_image(const std::string& path) {
  check_input_file(path, "image file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw make_error("image file ", path, " cannot be opened");
  }
  std::array<unsigned char, 8> head{};
  in.read(reinterpret_cast<char*>(head.data()), 8);
  if (in.gcount() >= 8 && png_sig_cmp(head.data(), 0, 8) == 0) {
    return read_png(path);
  }
  if (in.gcount() >= 2 && head[0] == 'P' && (head[1] == '2' || head[1] == '5')) {
    return read_pgm(path);
  }
  throw make_error("image file ", path, " is neither PNG nor PGM (P2/P5)");
}

void write_png(const Image& image, const std::string& path, int bit_depth) {
  check_bit_depth(bit_depth, path);
  check_image_size(image.width(), image.height(), "image for " + path);
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width());
  png.height = static_cast<png_uint_32>(image.height());
  png.format = bit_depth == 16 ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
  const int maxval = bit_depth == 16 ? 65535 : 255;
  int written = 0;
  if (bit_depth == 16) {
    std::vector<std::uint16_t> buffer(static_cast<std::size_t>(image.values.size()));
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        buffer[static_cast<std::size_t>(y) * image.width() + x] =
            quantize(image(x, y), maxval, path, x, y);
      }
    }
    written = png_image_write_to_file(&png, path.c_str(), 0, buffer.data(), 0, nullptr);
  } else {
    std::vector<std::uint8_t> buffer(static_cast<std::size_t>(image.values.size()));
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        buffer[static_cast<std::size_t>(y) * image.width() + x] =
            static_cast<std::uint8_t>(quantize(image(x, y), maxval, path, x, y));
      }
    }
    written = png_image_write_to_file(&png, path.c_str(), 0, buffer.data(), 0, nullptr);
  }
  if (written == 0) {
    throw make_error("PNG file ", path, " cannot be written: ", png.message);
  }
}

void write_pgm(const Image& image, const std::string& path, int bit_depth) {
  check_bit_depth(bit_depth, path);
  check_image_size(image.width(), image.height(), "image for " + path);
  const int maxval = bit_depth == 16 ? 65535 : 255;
  std::string data;
  data.reserve(static_cast<std::size_t>(image.values.size()) * (bit_depth / 8));
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const std::uint16_t sample = quantize(image(x, y), maxval, path, x, y);
      if (bit_depth == 16) {
        data.push_back(static_cast<char>(sample >> 8));
      }
      data.push_back(static_cast<char>(sample & 0xff));
    }
  }
  std::ofstream out(path, std::ios::binary);
  out << "P5\n" << image.width() << ' ' << image.height() << '\n' << maxval << '\n';
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  if (!out) {
    throw make_error("PGM file ", path, " cannot be written");
  }
}

}  // namespace dnurbs
