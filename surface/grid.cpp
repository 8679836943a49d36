#include "dnurbs/surface/grid.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"

namespace dnurbs {

Grid::Grid(int nu, int nv, double h, int minimum_nodes) : nu_(nu), nv_(nv), h_(h) {
  const int minimum = std::max(minimum_nodes, 2);
  if (nu < minimum || nv < minimum) {
    throw make_error("grid of ", nu, " by ", nv, " nodes is smaller than the ", minimum, " by ",
                     minimum, " nodes needed");
  }
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw make_error("grid spacing h = ", h, " is not positive and finite");
  }
}

Eigen::Vector2d Grid::parameter(int k) const {
  const auto [i, j] = node(k);
  return parameter(i, j);
}

std::vector<int> Grid::border_nodes() const {
  std::vector<int> nodes;
  for (int k = 0; k < node_count(); ++k) {
    const auto [i, j] = node(k);
    if (on_border(i, j)) {
      nodes.push_back(k);
    }
  }
  return nodes;
}

std::vector<Eigen::Vector2d> Grid::node_parameters() const {
  std::vector<Eigen::Vector2d> parameters;
  parameters.reserve(static_cast<size_t>(node_count()));
  for (int k = 0; k < node_count(); ++k) {
    parameters.push_back(parameter(k));
  }
  return parameters;
}

std::vector<Eigen::Vector2d> Grid::row_parameters(int j) const {
  if (j < 0 || j >= nv_) {
    throw make_error("grid row ", j, " is outside 0..", nv_ - 1);
  }
  std::vector<Eigen::Vector2d> parameters;
  parameters.reserve(static_cast<size_t>(nu_));
  for (int i = 0; i < nu_; ++i) {
    parameters.push_back(parameter(i, j));
  }
  return parameters;
}

std::array<std::pair<int, double>, 4> Grid::bilinear_weights(const Eigen::Vector2d& u) const {
  // Cell (i0, j0) and local coordinates (s, t) in [0, 1]; the last cell takes the far border.
  const auto locate = [this](double x, int n, int& cell, double& local) {
    double scaled = std::clamp(x / h_, 0.0, static_cast<double>(n - 1));
    // A parameter computed as i h lands exactly on node i (x / h may round to i - 1e-16).
    const double nearest = std::round(scaled);
    if (std::abs(scaled - nearest) <= 1e-9 * std::max(1.0, nearest)) {
      scaled = nearest;
    }
    cell = std::min(static_cast<int>(std::floor(scaled)), n - 2);
    local = scaled - cell;
  };
  int i0 = 0;
  int j0 = 0;
  double s = 0.0;
  double t = 0.0;
  locate(u.x(), nu_, i0, s);
  locate(u.y(), nv_, j0, t);
  return {{{index(i0, j0), (1.0 - s) * (1.0 - t)},
           {index(i0 + 1, j0), s * (1.0 - t)},
           {index(i0, j0 + 1), (1.0 - s) * t},
           {index(i0 + 1, j0 + 1), s * t}}};
}

ParameterDomain grid_parameter_domain(const Grid& grid) {
  ParameterDomain domain;
  domain.u_max = (grid.nu() - 1) * grid.spacing();
  domain.v_max = (grid.nv() - 1) * grid.spacing();
  return domain;
}

NodePositions flat_grid_positions(const Grid& grid, const Eigen::Vector3d& origin,
                                  const Eigen::Vector3d& axis_u, const Eigen::Vector3d& axis_v) {
  if (!origin.allFinite() || !axis_u.allFinite() || !axis_v.allFinite()) {
    throw make_error("flat grid origin or axes are not finite");
  }
  NodePositions positions(grid.node_count(), 3);
  for (int k = 0; k < grid.node_count(); ++k) {
    const Eigen::Vector2d p = grid.parameter(k);
    positions.row(k) = (origin + p.x() * axis_u + p.y() * axis_v).transpose();
  }
  return positions;
}

Eigen::Vector3d interpolate_grid(const Grid& grid, const NodePositions& positions,
                                 const Eigen::Vector2d& u) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (const auto& [node, weight] : grid.bilinear_weights(u)) {
    if (weight != 0.0) {
      x += weight * positions.row(node).transpose();
    }
  }
  return x;
}

void check_grid_positions(const Grid& grid, const NodePositions& positions, const char* what) {
  if (positions.rows() != grid.node_count()) {
    throw make_error(what, " has ", positions.rows(), " rows for a grid of ", grid.node_count(),
                     " nodes");
  }
  for (int k = 0; k < positions.rows(); ++k) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(positions(k, c))) {
        const auto [i, j] = grid.node(k);
        throw make_error(what, " of node (", i, ", ", j, ") coordinate ", c, " is ",
                         positions(k, c));
      }
    }
  }
}

TriangleMesh grid_triangle_mesh(const Grid& grid, const NodePositions& positions,
                                std::string name) {
  check_grid_positions(grid, positions, "mesh position");
  const int nu = grid.nu();
  const int nv = grid.nv();
  TriangleMesh mesh;
  mesh.name = std::move(name);
  mesh.vertices = positions;
  mesh.uv.resize(grid.node_count(), 2);
  mesh.normals.resize(grid.node_count(), 3);
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int k = grid.index(i, j);
      mesh.uv.row(k) = grid.parameter(i, j).transpose();
      // Central differences inside, one-sided on the border.
      const Eigen::Vector3d ru = positions.row(grid.index(std::min(i + 1, nu - 1), j)) -
                                 positions.row(grid.index(std::max(i - 1, 0), j));
      const Eigen::Vector3d rv = positions.row(grid.index(i, std::min(j + 1, nv - 1))) -
                                 positions.row(grid.index(i, std::max(j - 1, 0)));
      const Eigen::Vector3d n = ru.cross(rv);
      const double length = n.norm();
      mesh.normals.row(k) =
          length > 0.0 ? Eigen::RowVector3d((n / length).transpose()) : Eigen::RowVector3d::Zero();
    }
  }
  mesh.triangles.resize(2 * (nu - 1) * (nv - 1), 3);
  int t = 0;
  for (int j = 0; j + 1 < nv; ++j) {
    for (int i = 0; i + 1 < nu; ++i) {
      const int a = grid.index(i, j);
      const int b = grid.index(i + 1, j);
      const int c = grid.index(i + 1, j + 1);
      const int d = grid.index(i, j + 1);
      mesh.triangles.row(t++) << a, b, c;
      mesh.triangles.row(t++) << a, c, d;
    }
  }
  return mesh;
}

}  // namespace dnurbs
