#pragma once
// 3-D greyscale volumes as data for T-surfaces: a stack of 2-D slices (PNG/PGM) or a NRRD file
// (a small reader of the NRRD header of the Teem toolkit's format, raw/ASCII/gzip data).

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// Largest side a volume reader accepts.
inline constexpr int kMaxVolumeSide = 1 << 12;
/// Largest voxel count a volume reader accepts (256 M voxels, 2 GB of doubles).
inline constexpr long long kMaxVolumeVoxels = 1LL << 28;

/// A greyscale volume with double intensities.
///
/// size     {nx, ny, nz} voxel counts
/// values   nx * ny * nz intensities; voxel (x, y, z) at index x + nx * (y + ny * z)
/// spacing  3 distances between voxel centres (information kept from NRRD "spacings"; every
///          function of vision/ works in voxel units, voxel centres at integer (x, y, z))
struct Volume {
  std::array<int, 3> size{0, 0, 0};
  std::vector<double> values;
  Eigen::Vector3d spacing = Eigen::Vector3d::Ones();

  Volume() = default;
  /// An nx by ny by nz volume filled with `fill`. Throws Error naming the size if a side is not
  /// in [1, kMaxVolumeSide] or the voxel count exceeds kMaxVolumeVoxels.
  Volume(int nx, int ny, int nz, double fill = 0.0);

  long long index(int x, int y, int z) const {
    return x + static_cast<long long>(size[0]) * (y + static_cast<long long>(size[1]) * z);
  }
  double operator()(int x, int y, int z) const {
    return values[static_cast<std::size_t>(index(x, y, z))];
  }
  double& operator()(int x, int y, int z) {
    return values[static_cast<std::size_t>(index(x, y, z))];
  }
};

/// Throws Error naming `what`, the size and the limit if a side is outside [1, kMaxVolumeSide]
/// or the voxel count exceeds kMaxVolumeVoxels.
void check_volume_size(long long nx, long long ny, long long nz, const std::string& what);

/// Reads a volume from a stack of 2-D slices (PNG or PGM, see read_image), slice k at z = k.
/// Intensities are in [0, 1] as read_image gives them. Throws Error naming the slice file if
/// the list is empty, a slice cannot be read, or its size differs from the first slice's.
Volume read_volume_slices(const std::vector<std::string>& paths);

/// Reads a 3-D NRRD file (magic NRRD0001..NRRD0005). Supported: dimension 3; types signed and
/// unsigned 8/16/32-bit integers, float, double; encodings raw, ascii (text, txt) and gzip
/// (gz); endian little or big; data attached after the blank line or in a "data file" beside
/// the header; "line skip" and "byte skip" >= 0; optional "spacings". Values are kept as
/// stored (no scaling). Throws Error naming the file and the field or value for anything else:
/// a missing required field, an unknown type or encoding, sizes over the limits, truncated data.
Volume read_nrrd(const std::string& path);

/// Writes `volume` as a NRRD file with attached raw little-endian doubles (exact round trip
/// through read_nrrd) and its spacings. Throws Error naming the file if it cannot be written.
void write_nrrd(const Volume& volume, const std::string& path);

}  // namespace dnurbs
