#pragma once
// Scenes and measurements shared by the grid tests (Wu & de Melo's sheets on small grids).

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/surface/grid.h"

namespace dnurbs::test {

/// A square unit sheet of n by n nodes in the plane z = 0 (h = 1/(n-1), G0 = identity).
inline Grid unit_square_grid(int n) {
  return Grid(n, n, 1.0 / (n - 1));
}

inline TerzopoulosMaterial sheet_material(double eta_ii, double eta_12, double xi,
                                          double damping = 0.0) {
  TerzopoulosMaterial material;
  material.mass_density = 1.0;
  material.damping_density = damping;
  material.eta << eta_ii, eta_12, eta_12, eta_ii;
  material.xi << xi, xi, xi, xi;
  return material;
}

/// How far a displacement field on a square grid is from four-fold symmetry: the largest
/// |d(g k) - g d(k)| over the mirrors u -> -u, v -> -v and the diagonal swap u <-> v, relative
/// to the largest displacement.
inline double asymmetry(const Grid& grid, const NodePositions& displacement) {
  const int n = grid.nu();
  double worst = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::RowVector3d d = displacement.row(grid.index(i, j));
      const Eigen::RowVector3d mirror_u = displacement.row(grid.index(n - 1 - i, j));
      const Eigen::RowVector3d mirror_v = displacement.row(grid.index(i, n - 1 - j));
      const Eigen::RowVector3d swap = displacement.row(grid.index(j, i));
      worst = std::max(worst, (mirror_u - Eigen::RowVector3d(-d.x(), d.y(), d.z())).norm());
      worst = std::max(worst, (mirror_v - Eigen::RowVector3d(d.x(), -d.y(), d.z())).norm());
      worst = std::max(worst, (swap - Eigen::RowVector3d(d.y(), d.x(), d.z())).norm());
    }
  }
  const double scale = displacement.rowwise().norm().maxCoeff();
  return scale > 0.0 ? worst / scale : 0.0;
}

/// Tangential drift under a normal load: the largest in-plane displacement relative to the
/// largest normal (z) displacement, and the rotation about the centre (the "rotating" effect of
/// Wu & de Melo, figure 6): |sum (p x d)_z| / sum |p|^2 over the nodes, p the rest offset from the
/// centre, relative to the largest z displacement.
struct Drift {
  double tangential = 0.0;
  double rotation = 0.0;
};
inline Drift tangential_drift(const NodePositions& rest, const NodePositions& displacement) {
  const Eigen::Vector2d centre(rest.col(0).mean(), rest.col(1).mean());
  double moment = 0.0;
  double inertia = 0.0;
  double in_plane = 0.0;
  for (int k = 0; k < rest.rows(); ++k) {
    const Eigen::Vector2d p = Eigen::Vector2d(rest(k, 0), rest(k, 1)) - centre;
    const Eigen::Vector2d d(displacement(k, 0), displacement(k, 1));
    moment += p.x() * d.y() - p.y() * d.x();
    inertia += p.squaredNorm();
    in_plane = std::max(in_plane, d.norm());
  }
  const double normal = displacement.col(2).cwiseAbs().maxCoeff();
  if (normal == 0.0) {
    return {};
  }
  return {in_plane / normal, std::abs(moment) / inertia / normal};
}

/// Largest |B_ij| over the nodes (the maximum curvature of the sheet).
inline double max_curvature(const TerzopoulosSurface& surface, const Eigen::VectorXd& q) {
  return surface.tensors(q).curvature.cwiseAbs().maxCoeff();
}

}  // namespace dnurbs::test
