#pragma once
// Limits from memory, not only from counts: what a mesh or a model will need, estimated and
// checked against the memory the machine has available before anything is allocated, so that
// an oversized scene gets a message naming what to lower instead of std::bad_alloc or a
// machine that swaps.

#include <cstdint>
#include <string>

namespace dnurbs {

/// Bytes this process can still allocate without swapping: MemAvailable of /proc/meminfo (the
/// kernel's estimate), or the physical memory where that is not readable; at most the value of
/// the environment variable DNURBS_MEMORY_LIMIT (bytes) when that is set to a positive number
/// (to share a machine, or to test the limits).
std::uint64_t available_memory_bytes();

/// Throws Error "<what> needs about N MB, more than the M MB of memory available; lower
/// <lower>" if `bytes` (an estimate) exceeds available_memory_bytes(), or is not finite.
void check_memory_budget(double bytes, const std::string& what, const std::string& lower);

/// The memory of making and exporting a triangle mesh of `vertices` vertices and `triangles`
/// triangles. Measured: a 1920 x 1920-cell sheet (3.7e6 vertices) run and written as OBJ peaked
/// at 4.67 GB, 1265 B a vertex (the mesh in double, assimp's copy in single precision and the
/// OBJ exporter's vertex maps and text); taken as 650 B a vertex and 320 B a triangle.
inline double triangle_mesh_bytes(double vertices, double triangles) {
  return 650.0 * vertices + 320.0 * triangles;
}

}  // namespace dnurbs
