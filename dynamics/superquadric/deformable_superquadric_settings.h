#pragma once
// Settings of the deformable superquadric (dynamics/superquadric/deformable_superquadric_model.h):
// which parts of q = (c, theta, q_s, q_d) are free, the material, the mesh of the local
// displacements and the quadrature (Terzopoulos, "Deformable Models: Classic, Topology-Adaptive
// and Generalized Formulations", eqs. 1.28-1.38; Terzopoulos & Metaxas 1991).

#include <array>
#include <optional>

#include <Eigen/Core>

#include "dnurbs/surface/deformable_superquadric_shape.h"
#include "dnurbs/surface/parametric_fe_mesh.h"

namespace dnurbs {

/// Which parts of q = (c, theta, q_s, q_d) are free (Terzopoulos 2003, eq. 1.37).
struct DeformableSuperquadricParts {
  bool translation = true;  ///< c (3 coordinates, 3 velocities)
  bool rotation = true;     ///< quaternion (4 coordinates), body angular velocity (3 velocities)
  /// Free entries of q_s (indices SuperquadricShapeParameter::k...).
  std::array<bool, kSuperquadricShapeParameterCount> shape{};
  bool local = false;  ///< q_d, 3 per FE node

  /// A rigid body: translation and rotation only (6 velocities).
  static DeformableSuperquadricParts rigid();
  /// Rigid motion plus the global deformations a1, a2, a3, e1, e2, t1, t2, b1, tau, sx, sy
  /// (a is left out: it is redundant with a1..a3; b2, b3 are left out: they have no effect where
  /// b1 = 0). Free any q_s entry by setting shape[k].
  static DeformableSuperquadricParts global();
  /// global() plus the local displacements q_d.
  static DeformableSuperquadricParts full();

  bool operator==(const DeformableSuperquadricParts&) const = default;
};

/// Settings of a deformable superquadric model.
struct DeformableSuperquadricSettings {
  DeformableSuperquadricParts parts = DeformableSuperquadricParts::rigid();
  /// mu, mass per unit area of the reference shape (> 0).
  double mass_density = 1.0;
  /// Rayleigh damping D = alpha M + beta K (both >= 0).
  double damping_alpha = 0.0;
  double damping_beta = 0.0;
  /// Diagonal stiffness of each q_s entry toward its rest value: E_s = 1/2 sum k_i (q_s,i -
  /// rest_i)^2 over the free entries (>= 0).
  SuperquadricShapeParameters shape_stiffness = SuperquadricShapeParameters::Ones();
  /// Rest values of q_s; default: the construction shape.
  std::optional<SuperquadricShapeParameters> rest_shape;
  /// Local-displacement energy (membrane plus spring to the reference shape), ParametricFeMesh.
  FeStiffnessCoefficients local_stiffness{1.0, 1.0, 1.0};
  /// Cells of the (u, v) mesh: the FE mesh of q_d and the quadrature cells (>= 2 and >= 3).
  int mesh_cells_u = 8;
  int mesh_cells_v = 16;
  /// Gauss-Legendre points per direction and cell (1..kMaxGaussPoints).
  int quadrature_points = 3;
  /// Grade the rule toward the singular points of the area element (see the file comment):
  /// toward u = -pi/2, 0, pi/2 when e1 < 1 (cells end at the equator when mesh_cells_u is even)
  /// and toward v = k pi/2 when e2 < 1 (cells end there when mesh_cells_v is a multiple of 4),
  /// with the exponents of the construction shape.
  bool graded_quadrature = true;
  /// Relative extra inertia of the deformation coordinates (see the file comment), >= 0.
  /// Redundant directions (uniform d vs c, a vs a1..a3, b1 with b3 = 0, b2 and b3 with b1 = 0)
  /// move no material point, so M alone gives them no inertia while K may give them stiffness:
  /// their frequency is sqrt(k / (regularization M_kk)). 1e-3 keeps it within reach of an
  /// implicit step with Newton iterations (1e-8 makes undamped steps diverge) at the price of
  /// 0.1 % extra inertia on q_s and q_d; 0 is fine where M is regular (rigid or all-fixed
  /// redundancies). It never affects c and w, so momentum balances are unchanged.
  double regularization = 1e-3;
};

/// The name of shape parameter k ("squareness e1") for messages.
const char* superquadric_parameter_name(int k);

/// Throws Error naming the value unless the material values, shape stiffnesses, rest shape and
/// regularization are finite and in range (mass density > 0, the others >= 0).
void validate_superquadric_settings(const DeformableSuperquadricSettings& settings);

}  // namespace dnurbs
