#include "dnurbs/vision/t_surface.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

TetrahedralGrid grid_over_volume(const Volume& volume, const TSurfaceParameters& parameters) {
  // The umbrella Laplacian has eigenvalues in [0, 2], its square in [0, 4].
  parameters.validate("T-surface", 2.0, 4.0);
  const double cell_size = parameters.cell_size;
  Eigen::Vector3i cells;
  for (int axis = 0; axis < 3; ++axis) {
    cells[axis] =
        static_cast<int>(std::floor((volume.size[static_cast<std::size_t>(axis)] - 1) / cell_size));
  }
  return {Eigen::Vector3d::Zero(), cell_size, cells};
}

/// The mean over each vertex's mesh neighbors of `values` (#V by 3), neighbors by edges.
Eigen::MatrixX3d neighbor_mean(const std::vector<std::vector<int>>& neighbors,
                               const Eigen::MatrixX3d& values) {
  Eigen::MatrixX3d mean = Eigen::MatrixX3d::Zero(values.rows(), 3);
  for (std::size_t i = 0; i < neighbors.size(); ++i) {
    for (const int j : neighbors[i]) {
      mean.row(static_cast<Eigen::Index>(i)) += values.row(j);
    }
    mean.row(static_cast<Eigen::Index>(i)) /=
        static_cast<double>(std::max<std::size_t>(neighbors[i].size(), 1));
  }
  return mean;
}

}  // namespace

TSurface::TSurface(const Volume& volume, VolumeEdgePotential potential,
                   const TSurfaceParameters& parameters)
    : volume_(volume),
      potential_(std::move(potential)),
      parameters_(parameters),
      grid_(grid_over_volume(volume, parameters)) {
  if (volume.size != potential_.samples().size) {
    throw make_error("T-surface volume is ", volume.size[0], " by ", volume.size[1], " by ",
                     volume.size[2], ", its edge potential ", potential_.samples().size[0], " by ",
                     potential_.samples().size[1], " by ", potential_.samples().size[2]);
  }
  if (!std::all_of(volume.values.begin(), volume.values.end(),
                   [](double value) { return std::isfinite(value); })) {
    throw make_error("T-surface volume has a voxel that is not finite");
  }
  inside_.assign(static_cast<std::size_t>(grid_.vertex_count()), 0);
  mesh_.name = "t_surface";
  mesh_.vertices.resize(0, 3);
  mesh_.triangles.resize(0, 3);
}

double TSurface::intensity(const Eigen::Vector3d& point) const {
  std::array<int, 3> base{};
  std::array<double, 3> t{};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double x =
        std::clamp(point[static_cast<Eigen::Index>(axis)], 0.0, volume_.size[axis] - 1.0);
    base[axis] = std::min(static_cast<int>(x), volume_.size[axis] - 2);
    t[axis] = x - base[axis];
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1;
    const int dy = (corner >> 1) & 1;
    const int dz = (corner >> 2) & 1;
    const double weight = (dx != 0 ? t[0] : 1.0 - t[0]) * (dy != 0 ? t[1] : 1.0 - t[1]) *
                          (dz != 0 ? t[2] : 1.0 - t[2]);
    value += weight * volume_(base[0] + dx, base[1] + dy, base[2] + dz);
  }
  return value;
}

Eigen::MatrixX3d TSurface::vertex_forces() const {
  const Eigen::Index n = mesh_.vertices.rows();
  std::vector<std::vector<int>> neighbors(static_cast<std::size_t>(n));
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(n, 3);
  for (Eigen::Index f = 0; f < mesh_.triangles.rows(); ++f) {
    const Eigen::Vector3d a = mesh_.vertices.row(mesh_.triangles(f, 0));
    const Eigen::Vector3d b = mesh_.vertices.row(mesh_.triangles(f, 1));
    const Eigen::Vector3d c = mesh_.vertices.row(mesh_.triangles(f, 2));
    const Eigen::RowVector3d area_normal = 0.5 * (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) {
      const int v = mesh_.triangles(f, k);
      normals.row(v) += area_normal;
      // Each edge appears in both of its triangles; the neighbor is recorded from one direction.
      neighbors[static_cast<std::size_t>(v)].push_back(mesh_.triangles(f, (k + 1) % 3));
    }
  }
  // Membrane and thin-plate differences (the umbrella operator and its square).
  const Eigen::MatrixX3d alpha = mesh_.vertices - neighbor_mean(neighbors, mesh_.vertices);
  const Eigen::MatrixX3d beta = alpha - neighbor_mean(neighbors, alpha);
  Eigen::MatrixX3d forces(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d x = mesh_.vertices.row(i).transpose();
    const double norm = normals.row(i).norm();
    const Eigen::RowVector3d normal =
        norm > 0.0 ? Eigen::RowVector3d(normals.row(i) / norm) : Eigen::RowVector3d::Zero();
    const double value = intensity(x);
    const double switch_value =
        inflation_switch(value, parameters_.threshold, parameters_.inflation_band);
    forces.row(i) = -parameters_.tension * alpha.row(i) - parameters_.rigidity * beta.row(i) +
                    parameters_.inflation * switch_value * normal -
                    parameters_.edge_weight * potential_.gradient(x).transpose();
  }
  return forces;
}

bool TSurface::reparameterize() {
  const TetrahedralCrossings crossings(grid_, mesh_);
  std::vector<char> inside = inside_vertices(grid_, crossings);
  mesh_ = boundary_mesh(grid_, inside,
                        [&](int family, const Eigen::Vector3i& first, bool first_inside) {
                          return crossing_fraction(crossings, family, first, first_inside);
                        });
  const bool changed = inside != inside_;
  inside_ = std::move(inside);
  return changed;
}

void TSurface::add_implicit(const std::function<double(const Eigen::Vector3d&)>& level) {
  std::vector<double> values(static_cast<std::size_t>(grid_.vertex_count()));
  const Eigen::Vector3i n = grid_.cells();
  for (int k = 0; k <= n.z(); ++k) {
    for (int j = 0; j <= n.y(); ++j) {
      for (int i = 0; i <= n.x(); ++i) {
        const Eigen::Vector3i g(i, j, k);
        const double value = level(grid_.vertex_position(g));
        if (std::isnan(value)) {
          throw make_error("T-surface implicit seed is NaN at grid vertex (", i, ", ", j, ", ", k,
                           ")");
        }
        values[static_cast<std::size_t>(grid_.vertex_index(g))] = value;
      }
    }
  }
  // The seed's own boundary mesh, then the union with the current surface by winding numbers.
  std::vector<char> seed(values.size());
  std::transform(values.begin(), values.end(), seed.begin(),
                 [](double v) { return v < 0.0 ? 1 : 0; });
  const TriangleMesh seed_mesh = boundary_mesh(
      grid_, seed, [&](int family, const Eigen::Vector3i& first, bool /*first_inside*/) {
        const double a = values[static_cast<std::size_t>(grid_.vertex_index(first))];
        const double b = values[static_cast<std::size_t>(
            grid_.vertex_index(first + TetrahedralGrid::direction(family)))];
        return std::clamp(a / (a - b), kAcidEdgeMargin, 1.0 - kAcidEdgeMargin);
      });
  const Eigen::Index v0 = mesh_.vertices.rows();
  TriangleMesh joined = mesh_;
  joined.vertices.conservativeResize(v0 + seed_mesh.vertices.rows(), 3);
  joined.vertices.bottomRows(seed_mesh.vertices.rows()) = seed_mesh.vertices;
  joined.triangles.conservativeResize(mesh_.triangles.rows() + seed_mesh.triangles.rows(), 3);
  joined.triangles.bottomRows(seed_mesh.triangles.rows()) =
      seed_mesh.triangles.array() + static_cast<int>(v0);
  mesh_ = std::move(joined);
  reparameterize();
}

void TSurface::add_sphere(const Eigen::Vector3d& center, double radius) {
  if (!center.allFinite() || !(std::isfinite(radius) && radius > 0.0)) {
    throw make_error("T-surface sphere of radius ", radius, " at (", center.x(), ", ", center.y(),
                     ", ", center.z(), ") is not finite with radius > 0");
  }
  add_implicit([&](const Eigen::Vector3d& p) { return (p - center).norm() - radius; });
}

bool TSurface::step() {
  const double scale = parameters_.time_step / parameters_.damping;
  const Eigen::RowVector3d low = grid_.origin().transpose();
  const Eigen::RowVector3d high =
      low + grid_.cell_size() * grid_.cells().cast<double>().transpose();
  mesh_.vertices += scale * vertex_forces();
  for (Eigen::Index i = 0; i < mesh_.vertices.rows(); ++i) {
    mesh_.vertices.row(i) = mesh_.vertices.row(i).cwiseMax(low).cwiseMin(high);
  }
  ++steps_;
  if (steps_ % parameters_.steps_per_reparameterization != 0) {
    return false;
  }
  return reparameterize();
}

int TSurface::run(int max_steps, int stable_steps) {
  int stable = 0;
  int taken = 0;
  while (taken < max_steps && stable < stable_steps && mesh_.triangle_count() > 0) {
    stable = step() ? 0 : stable + 1;
    ++taken;
  }
  return taken;
}

}  // namespace dnurbs
