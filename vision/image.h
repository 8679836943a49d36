#pragma once
// 2-D greyscale images as data for snakes: reading and writing PNG (through libpng) and PGM
// (a bounded reader and writer of the Netpbm P2/P5 formats).

#include <string>

#include <Eigen/Core>

namespace dnurbs {

/// Largest width or height a reader accepts; larger headers are rejected before allocating.
inline constexpr int kMaxImageSide = 1 << 15;
/// Largest pixel count a reader accepts (256 M pixels, 2 GB of doubles).
inline constexpr long long kMaxImagePixels = 1LL << 28;

/// A greyscale image with double intensities.
///
/// values  width by height array; values(x, y) is the pixel in column x, row y (row 0 is the
///         first row of the file). Pixel centres sit at integer (x, y) in pixel units, which is
///         the coordinate frame every function of vision/ uses for points in the image.
/// Intensities read from files are scaled to [0, 1] (value / maxval); any finite value may be
/// stored, writers clamp to [0, 1].
struct Image {
  Eigen::ArrayXXd values;

  Image() = default;
  /// A width by height image filled with `fill`. Throws Error naming the size if it is not
  /// positive or exceeds kMaxImageSide / kMaxImagePixels.
  Image(int width, int height, double fill = 0.0);

  int width() const { return static_cast<int>(values.rows()); }
  int height() const { return static_cast<int>(values.cols()); }
  double operator()(int x, int y) const { return values(x, y); }
  double& operator()(int x, int y) { return values(x, y); }
};

/// Throws Error naming `what`, the size and the limit if width or height is not in
/// [1, kMaxImageSide] or their product exceeds kMaxImagePixels.
void check_image_size(long long width, long long height, const std::string& what);

/// Reads an 8- or 16-bit PNG (grey, grey+alpha, palette or RGB(A); color is converted to grey
/// with the Rec. 709 luminance weights by libpng, alpha is dropped). Throws Error naming the
/// file on any libpng error, a missing file or a size over the limits.
Image read_png(const std::string& path);

/// Reads a PGM file: P2 (ASCII) or P5 (binary, 8-bit, or 16-bit big-endian when maxval > 255),
/// with '#' comments in the header. Throws Error naming the file and the bad value for a wrong
/// magic number, a size over the limits, maxval outside [1, 65535], a sample above maxval or
/// truncated data.
Image read_pgm(const std::string& path);

/// Reads a PNG or PGM file, chosen by its first bytes (the PNG signature or "P2"/"P5").
Image read_image(const std::string& path);

/// Writes `image` as an 8-bit (bit_depth 8) or 16-bit (bit_depth 16) greyscale PNG; values are
/// clamped to [0, 1] and rounded. Throws Error naming the file if it cannot be written, for a
/// bit depth other than 8 or 16, or an image holding NaN.
void write_png(const Image& image, const std::string& path, int bit_depth = 8);

/// Writes `image` as a binary PGM (P5) with maxval 255 (bit_depth 8) or 65535 (bit_depth 16);
/// values are clamped to [0, 1] and rounded. Same errors as write_png.
void write_pgm(const Image& image, const std::string& path, int bit_depth = 8);

}  // namespace dnurbs
