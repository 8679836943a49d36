#include "dnurbs/surface/tessellation.h"

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/core/memory_budget.h"

namespace dnurbs {
namespace {

// Uniform parameters over a knot vector's domain: segments + 1 with both ends for an open one,
// `segments` without the end (which is the start again) for a periodic one.
std::vector<double> uniform_parameters(const KnotVector& knots, int segments) {
  const double start = knots.domain_start();
  const double end = knots.domain_end();
  const int count = knots.is_periodic() ? segments : segments + 1;
  std::vector<double> parameters(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    parameters[static_cast<size_t>(i)] = start + (end - start) * i / segments;
  }
  if (!knots.is_periodic()) {
    parameters.back() = end;  // exactly the end, not start + (end - start) rounded
  }
  return parameters;
}

void check_segments(const KnotVector& knots, int segments, const char* what) {
  const int minimum = knots.is_periodic() ? 3 : 1;
  if (segments < minimum) {
    throw make_error("tessellation: ", what, " resolution ", segments, " is below ", minimum,
                     knots.is_periodic() ? " (periodic direction)" : "");
  }
}

// A mesh named `name` with room for vertex_count vertices, normals and texture coordinates.
TriangleMesh sized_mesh(std::string name, int vertex_count) {
  TriangleMesh mesh;
  mesh.name = std::move(name);
  mesh.vertices.resize(vertex_count, 3);
  mesh.normals.resize(vertex_count, 3);
  mesh.uv.resize(vertex_count, 2);
  return mesh;
}

// Two triangles per cell of a grid of rows by columns samples, sample (i, j) at row
// i * columns + j: the cells (i, j), i < cell_rows, j < cell_columns, with corners a = (i, j),
// b = (i + 1, j), c = (i + 1, j + 1), d = (i, j + 1), split into (a, b, c) and (a, c, d), or
// into (a, c, b) and (a, d, c) when `reversed`. The corner indices wrap (i + 1 = rows is row 0,
// j + 1 = columns is column 0), so that a periodic direction's last cells close the mesh.
// #cells * 2 by 3.
Eigen::MatrixX3i grid_triangles(int rows, int columns, int cell_rows, int cell_columns,
                                bool reversed) {
  Eigen::MatrixX3i triangles(2 * cell_rows * cell_columns, 3);
  int triangle = 0;
  for (int i = 0; i < cell_rows; ++i) {
    const int i1 = (i + 1) % rows;
    for (int j = 0; j < cell_columns; ++j) {
      const int j1 = (j + 1) % columns;
      const int a = i * columns + j;
      const int b = i1 * columns + j;
      const int c = i1 * columns + j1;
      const int d = i * columns + j1;
      if (reversed) {
        triangles.row(triangle++) << a, c, b;
        triangles.row(triangle++) << a, d, c;
      } else {
        triangles.row(triangle++) << a, b, c;
        triangles.row(triangle++) << a, c, d;
      }
    }
  }
  return triangles;
}

}  // namespace

TriangleMesh tessellate_surface(const NurbsSurface& surface, int segments_u, int segments_v,
                                std::string name) {
  check_segments(surface.knots_u(), segments_u, "u");
  check_segments(surface.knots_v(), segments_v, "v");
  const double vertices = (segments_u + 1.0) * (segments_v + 1.0);
  check_memory_budget(
      triangle_mesh_bytes(vertices, 2.0 * vertices),
      "a mesh of " + std::to_string(segments_u) + " x " + std::to_string(segments_v) + " cells",
      "the mesh resolution");
  const std::vector<double> us = uniform_parameters(surface.knots_u(), segments_u);
  const std::vector<double> vs = uniform_parameters(surface.knots_v(), segments_v);
  const int count_u = static_cast<int>(us.size());
  const int count_v = static_cast<int>(vs.size());

  TriangleMesh mesh = sized_mesh(std::move(name), count_u * count_v);
  // Sample points, normals and parameters, u outer
  for (int i = 0; i < count_u; ++i) {
    for (int j = 0; j < count_v; ++j) {
      const int row = i * count_v + j;
      const double u = us[static_cast<size_t>(i)];
      const double v = vs[static_cast<size_t>(j)];
      mesh.vertices.row(row) = surface.point(u, v).transpose();
      mesh.normals.row(row) = surface.unit_normal(u, v).transpose();
      mesh.uv.row(row) << u, v;
    }
  }
  // Two triangles per cell (a, b, c) and (a, c, d), with a = (i, j), b = (i + 1, j),
  // c = (i + 1, j + 1), d = (i, j + 1); (b - a) x (c - a) ~ Su x Sv du dv. Periodic directions
  // wrap their last cell to the first sample.
  mesh.triangles = grid_triangles(count_u, count_v, segments_u, segments_v, /*reversed=*/false);
  return mesh;
}

Eigen::MatrixX3d sample_curve(const NurbsCurve& curve, int segments) {
  check_segments(curve.knots(), segments, "curve");
  const std::vector<double> us = uniform_parameters(curve.knots(), segments);
  Eigen::MatrixX3d points(static_cast<int>(us.size()), 3);
  for (int k = 0; k < points.rows(); ++k) {
    points.row(k) = curve.point(us[static_cast<size_t>(k)]).transpose();
  }
  return points;
}

TriangleMesh tessellate_curve_tube(const NurbsCurve& curve, int segments, double radius, int sides,
                                   std::string name) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw make_error("tessellation: tube radius ", radius, " is not a positive finite number");
  }
  if (sides < 3) {
    throw make_error("tessellation: tube sides ", sides, " is below 3");
  }
  check_segments(curve.knots(), segments, "curve");
  const double vertices = (segments + 1.0) * sides;
  check_memory_budget(
      triangle_mesh_bytes(vertices, 2.0 * vertices),
      "a tube of " + std::to_string(segments) + " x " + std::to_string(sides) + " cells",
      "the mesh resolution");
  const std::vector<double> us = uniform_parameters(curve.knots(), segments);
  const int rings = static_cast<int>(us.size());
  const bool closed = curve.is_periodic();

  // Rotation-minimizing frame: project the previous normal onto each new normal plane
  std::vector<Eigen::Vector3d> tangents(static_cast<size_t>(rings));
  std::vector<Eigen::Vector3d> normals(static_cast<size_t>(rings));
  for (int k = 0; k < rings; ++k) {
    tangents[static_cast<size_t>(k)] = curve.unit_tangent(us[static_cast<size_t>(k)]);
  }
  {
    const Eigen::Vector3d& t0 = tangents[0];
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    if (std::abs(t0.x()) > 0.9) {
      axis = Eigen::Vector3d::UnitY();
    }
    normals[0] = (axis - axis.dot(t0) * t0).normalized();
  }
  auto transport = [](const Eigen::Vector3d& normal, const Eigen::Vector3d& tangent) {
    Eigen::Vector3d projected = normal - normal.dot(tangent) * tangent;
    if (projected.norm() < 1e-12) {
      throw make_error(
          "tessellation: tube frame degenerates (the curve turns by 90 degrees "
          "between two samples); raise the resolution");
    }
    return Eigen::Vector3d(projected.normalized());
  };
  for (int k = 1; k < rings; ++k) {
    normals[static_cast<size_t>(k)] =
        transport(normals[static_cast<size_t>(k - 1)], tangents[static_cast<size_t>(k)]);
  }
  if (closed) {
    // Spread the twist that the transported frame has gathered at the seam along the curve
    const Eigen::Vector3d back = transport(normals.back(), tangents[0]);
    const double twist = std::atan2(normals[0].cross(back).dot(tangents[0]), normals[0].dot(back));
    for (int k = 1; k < rings; ++k) {
      const double angle = -twist * k / rings;
      normals[static_cast<size_t>(k)] = Eigen::AngleAxisd(angle, tangents[static_cast<size_t>(k)]) *
                                        normals[static_cast<size_t>(k)];
    }
  }

  TriangleMesh mesh = sized_mesh(std::move(name), rings * sides);
  const Eigen::MatrixX3d centres = sample_curve(curve, segments);
  for (int k = 0; k < rings; ++k) {
    const Eigen::Vector3d& t = tangents[static_cast<size_t>(k)];
    const Eigen::Vector3d& n = normals[static_cast<size_t>(k)];
    const Eigen::Vector3d b = t.cross(n);
    for (int s = 0; s < sides; ++s) {
      const double angle = 2.0 * std::numbers::pi * s / sides;
      const Eigen::Vector3d offset = std::cos(angle) * n + std::sin(angle) * b;
      const int row = k * sides + s;
      mesh.vertices.row(row) = centres.row(k) + radius * offset.transpose();
      mesh.normals.row(row) = offset.transpose();
      mesh.uv.row(row) << us[static_cast<size_t>(k)], static_cast<double>(s) / sides;
    }
  }
  // Quads between consecutive rings, split as (a, c, b) and (a, d, c) so that the triangles face
  // outwards: along the ring the direction is d offset / d angle, and T x that is -offset.
  const int bands = closed ? rings : rings - 1;
  mesh.triangles = grid_triangles(rings, sides, bands, sides, /*reversed=*/true);
  return mesh;
}

}  // namespace dnurbs
