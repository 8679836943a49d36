#pragma once
// Topology-adaptive deformable surfaces (T-surfaces) (Terzopoulos, Deformable Models: Classic,
// Topology-Adaptive and Generalized Formulations, section 3.2; McInerney & Terzopoulos, Topology
// adaptive deformable surfaces for medical image volume segmentation, IEEE TMI 18(10) 1999): a
// closed triangle mesh driven by membrane tension, thin-plate rigidity, an inflation force
// switched by the volume intensity and the edge force -grad P, reparameterized on a tetrahedral
// ACID (cubes split into 6 tetrahedra) after every M steps, so it changes topology.

#include <functional>

#include <Eigen/Core>

#include "dnurbs/surface/triangle_mesh.h"
#include "dnurbs/vision/tetrahedral_decomposition.h"
#include "dnurbs/vision/tetrahedral_grid.h"
#include "dnurbs/vision/topology_adaptive_parameters.h"
#include "dnurbs/vision/volume.h"
#include "dnurbs/vision/volume_edge_potential.h"

namespace dnurbs {

/// The parameters of T-surfaces (voxel units; TopologyAdaptiveParameters lists them).
///
/// The explicit step of every mesh vertex, the discrete deformable surface with mu = 0
/// (Terzopoulos, eq. 1.20 with the umbrella Laplacian as the discrete membrane and thin plate):
///   x_i <- x_i + (time_step / damping) (-tension alpha_i - rigidity beta_i + rho_i + f_i)
/// with alpha_i = x_i - mean of the neighbors x_j, beta_i = alpha_i - mean of the neighbors
/// alpha_j, rho_i = inflation F(V(x_i)) n_i (n_i the area-weighted outward vertex normal, F the
/// inflation_switch), and f_i = -edge_weight grad P(x_i); V is the volume trilinearly
/// interpolated. Defaults as TopologyAdaptiveParameters except tension 0.2, time_step 0.25 and
/// the ramp switch with inflation_band 0.25.
struct TSurfaceParameters : TopologyAdaptiveParameters {
  TSurfaceParameters() {
    tension = 0.2;
    time_step = 0.25;
    inflation_band = 0.25;
  }
};

/// A T-surface in one volume. The grid covers the volume: cells of side cell_size from (0, 0, 0),
/// floor((n - 1) / cell_size) per axis. The mesh is the boundary of the inside grid vertices:
/// closed, manifold, triangles counter-clockwise seen from outside, possibly several components.
class TSurface {
 public:
  /// Throws Error as TopologyAdaptiveParameters::validate (the largest eigenvalues of the
  /// umbrella alpha and of beta are 2 and 4), for a volume whose size differs from the
  /// potential's or a voxel that is not finite.
  TSurface(const Volume& volume, VolumeEdgePotential potential,
           const TSurfaceParameters& parameters);

  /// Adds the region where `level` < 0 (union with the current inside region); the new boundary
  /// nodes sit where `level`, linear along each grid edge, is 0.
  void add_implicit(const std::function<double(const Eigen::Vector3d&)>& level);
  /// Adds a ball of `radius` about `center`.
  void add_sphere(const Eigen::Vector3d& center, double radius);

  /// One deformation step and, every M steps, the reparameterization. Returns true if the inside
  /// grid vertices changed.
  bool step();
  /// Steps until the inside vertices are unchanged for `stable_steps` steps or `max_steps` steps.
  int run(int max_steps, int stable_steps = 30);

  /// The bracketed force sum of the step at every mesh vertex (#V by 3).
  Eigen::MatrixX3d vertex_forces() const;
  /// The volume intensity at a point, trilinear between voxels (clamped to the volume).
  double intensity(const Eigen::Vector3d& point) const;

  /// vertices #V by 3, triangles #F by 3.
  const TriangleMesh& mesh() const { return mesh_; }
  const std::vector<char>& inside() const { return inside_; }
  const TetrahedralGrid& grid() const { return grid_; }

 private:
  bool reparameterize();

  Volume volume_;
  VolumeEdgePotential potential_;
  TSurfaceParameters parameters_;
  TetrahedralGrid grid_;
  TriangleMesh mesh_;
  std::vector<char> inside_;
  int steps_ = 0;
};

}  // namespace dnurbs
