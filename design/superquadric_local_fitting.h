#pragma once
// The local stage of the superquadric fit: the displacement field d = S q_d of a deformable
// superquadric (Terzopoulos, "Deformable Models", eqs. 1.29, 1.32-1.33) fitted to points once the
// pose and the reference shape s (eq. 1.30) are known, so that the fitted surface
// x = c + R (s + d) (eq. 1.35) captures detail the global shape cannot.
//
// d lives on the model's own finite-element mesh (surface/parametric_fe_mesh.h: bilinear C0
// cells in (u, v), closed at the poles, periodic in v) and is regularized by the model's own
// local-deformation energy E_d = 1/2 q_d^T K_d q_d, K_d = ParametricFeMesh::stiffness_matrix (a
// membrane plus a spring to the reference shape, as DeformableSuperquadricModel uses). Each point
// x_k pulls on the material point u_k of the reference shape that the radial distance measures to
// (superquadric_radial_projection) with a data spring of stiffness kappa = 1 / (N lambda),
// lambda = `smoothness`, N the number of points. The fit is the static equilibrium of
// eq. 1.38 for the q_d block (qdot = qddot = 0, so g_q = 0), K_d q_d = f_q, with the generalized
// data force f_q = sum_k S_k^T kappa (p_k - s_k - S_k q_d) in the body frame,
// p_k = R^T (x_k - c), s_k = s(u_k), S_k = S(u_k):
//
//   (K_d + kappa sum_k S_k^T S_k) q_d = kappa sum_k S_k^T (p_k - s_k),
//
// i.e. the minimizer of (1/2N) sum_k |p_k - s_k - S_k q_d|^2 + (lambda/2) q_d^T K_d q_d. Both
// matrices are k (x) I_3 of scalar node matrices, so one sparse Cholesky factor of the scalar
// matrix solves x, y and z.
//
// Bias: the energy smooths what it fits. For data of density rho per unit (u, v) area sampling
// a displacement b, the continuous equilibrium is d - N lambda / rho (w_u d_uu + w_v d_vv) +
// N lambda k_0 / rho d = b, so to first order d = b + (N lambda / rho)(w_u b_uu + w_v b_vv -
// k_0 b): a bump is fitted lower than it is by that much at its peak.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/surface/deformable_superquadric_shape.h"
#include "dnurbs/surface/parametric_fe_mesh.h"

namespace dnurbs {

struct SuperquadricLocalFitSettings {
  /// Cells of the (u, v) mesh of d (>= 2 and >= 3), as DeformableSuperquadricSettings.
  int mesh_cells_u = 8;
  int mesh_cells_v = 16;
  /// The model's local-deformation energy (coefficients >= 0, not all zero).
  FeStiffnessCoefficients stiffness{1.0, 1.0, 0.0};
  /// lambda > 0: the weight of E_d against the mean squared data distance.
  double smoothness = 1e-4;
};

struct SuperquadricLocalFitResult {
  int mesh_cells_u = 0;
  int mesh_cells_v = 0;
  /// q_d, 3 #nodes, body frame, ordered like ParametricFeMesh (the model's q_d block).
  Eigen::VectorXd displacements;
  /// The material points (u, v) of the points, #points by 2.
  Eigen::MatrixX2d parameters;
  /// rms and max of |x_k - x(u_k)|, x = c + R (s + d), with the fitted d ...
  double rms_error = 0.0;
  double max_error = 0.0;
  /// ... and with d = 0 (the global shape alone, same material points).
  double global_rms_error = 0.0;
  double global_max_error = 0.0;
};

/// Throws Error naming the value unless the mesh cells, stiffness and smoothness are valid.
void validate_superquadric_local_fit_settings(const SuperquadricLocalFitSettings& settings);

/// Fits the local displacements to `points` (#points by 3, world frame) on the superquadric
/// (shape q_s 14-vector, centre, rotation body to world) by the equilibrium in the file comment.
/// Throws Error for empty or non-finite points, bad settings or a point without a radial
/// projection. Fewer points than nodes are fine: E_d determines the nodes the data leave free.
SuperquadricLocalFitResult fit_superquadric_local_displacements(
    const Eigen::MatrixX3d& points, const SuperquadricShapeParameters& shape,
    const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
    const SuperquadricLocalFitSettings& settings = {});

}  // namespace dnurbs
