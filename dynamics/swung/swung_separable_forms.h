#pragma once
// The separable fast path of swung D-NURBS surfaces with fixed weights and constant material
// (Qin & Terzopoulos, Dynamic NURBS swung surfaces for physics-based shape design, CAD 27(2)
// 1995; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized
// Formulations, eqs. 1.20 and 1.25).
//
// With fixed weights each curve is linear in its coordinates, f^(k)(u) = R^(k)(u) . x,
// h^(k)(u) = R^(k)(u) . z, t^(l)(v) = (R^(l)(v) . X, R^(l)(v) . Y), and every integrand of the
// model is a product of a function of u and a function of v. With constant mu, gamma and k_Q
// the double integrals are products of single ones, all quadratic forms of the 1-D Gram
// matrices A_k = integral R^(k) R^(k)^T du (profile) and B_l = integral R^(l) R^(l)^T dv
// (trajectory), computed once. With F_k = x^T A_k x, G_l = X^T B_l X + Y^T B_l Y,
// H_k = z^T A_k z and L_v the length of the v domain:
//   E = 1/2 sum_Q k_Q (alpha^2 F_k G_l + [l == 0] L_v H_k)                     (Q = (k, l)),
//   M: xx = mu alpha^2 G_0 A_0, zz = mu L_v A_0, XX = YY = mu alpha^2 F_0 B_0,
//      xX = mu alpha^2 (A_0 x)(B_0 X)^T, xY = mu alpha^2 (A_0 x)(B_0 Y)^T,
//   g = -integral mu J^T (2 alpha f' t', 0): x: -2 mu alpha^2 (A_0 xd)(X . B_0 Xd + Y . B_0 Yd),
//      X: -2 mu alpha^2 (x . A_0 xd) B_0 Xd (Y likewise),
//   d^2E/dq^2: xx = sum k alpha^2 G_l A_k, zz = sum k [l == 0] L_v A_k, XX = YY = sum k alpha^2
//      F_k B_l, xX = 2 sum k alpha^2 (A_k x)(B_l X)^T (the Gauss-Newton part has factor 1).
// An assembly costs O((m + n)^2) instead of O(N_u N_v (p + q)^2) Gauss-point work, and gives the
// same sums as the general quadrature up to round-off (the same Gauss points, regrouped).
//
// With a rest shape q_r = (x_r, z_r, X_r, Y_r) the energy is that of the change from it,
// E = 1/2 integral sum_Q k_Q |S^Q(q) - S^Q(q_r)|^2 (dnurbs_swung_surface.h). Writing
// f t - f_r t_r = (f - f_r) t + f_r (t - t_r) and dx = x - x_r, dT = T - T_r (T = (X, Y), B_l
// acting on X and Y alike):
//   E = 1/2 sum_Q k_Q (alpha^2 [dx^T A_k dx G_l + 2 (dx^T A_k x_r)(T^T B_l dT)
//                               + (x_r^T A_k x_r)(dT^T B_l dT)] + [l == 0] L_v dz^T A_k dz),
//   -f_int: x: k alpha^2 (G_l A_k dx + (T^T B_l dT) A_k x_r), z: [l == 0] k L_v A_k dz,
//           T: k alpha^2 ((dx^T A_k x) B_l T + (x_r^T A_k x) B_l dT),
// every term a product with dx, dz or dT, so that E and f_int vanish exactly at q = q_r (and
// rounding is relative to the change, not to |q|^2). The Gauss-Newton part of d^2E/dq^2 does not
// depend on q_r; the exact tangent's cross block is k alpha^2 (2 (A_k x)(B_l T)^T -
// (A_k x_r)(B_l T_r)^T). Without a rest shape q_r = 0 and these are the forms above.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/swung/swung_quadrature.h"
#include "dnurbs/nurbs/swung_jacobian.h"

namespace dnurbs {

/// The Gram matrices of both curves and the quadratic forms built from them. Valid only for
/// fixed weights and constant material (the caller checks); the Gram matrices depend only on
/// the knots, the fixed weights and the rule, so they are computed once.
class SwungSeparableForms {
 public:
  SwungSeparableForms() = default;
  /// `profile` / `trajectory`: rational samples of the curves at their Gauss points (for fixed
  /// weights they do not depend on q). `material`: the constant values in SwungQuadrature's
  /// layout (kSwungMaterialStride entries).
  SwungSeparableForms(const SwungQuadrature& quadrature, const SwungLayout& layout, double alpha,
                      const std::vector<PlanarCurveSample>& profile,
                      const std::vector<PlanarCurveSample>& trajectory, const double* material);

  /// Measures E, f_int and the exact tangent from the rest shape at coordinates `q_rest` (file
  /// comment); the constructor's rest is q_r = 0 (the energy measured from zero).
  void set_rest(const Eigen::Ref<const Eigen::VectorXd>& q_rest);

  /// Sets the dense #coordinates square matrices M, D (if damping is non-zero; `damping` is
  /// left alone otherwise) and the stiffness (exact tangent, or only its Gauss-Newton part).
  void matrices(const Eigen::Ref<const Eigen::VectorXd>& q, bool geometric_stiffness,
                Eigen::MatrixXd& mass, Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness) const;
  double energy(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// force -= dE/dq.
  void add_internal_force(const Eigen::Ref<const Eigen::VectorXd>& q,
                          Eigen::Ref<Eigen::VectorXd> force) const;
  /// force += g(q, qd).
  void add_inertial_force(const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& qd,
                          Eigen::Ref<Eigen::VectorXd> force) const;

 private:
  // The coordinates of q by kind: profile x and z, trajectory X and Y.
  struct Split {
    Eigen::VectorXd profile_x, profile_z, trajectory_x, trajectory_y;
  };
  Split split(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // s - rest_, kind by kind.
  Split change(const Split& s) const;
  // Adds a block of coordinates (rows of kind r, columns of kind c; kinds 0 x, 1 z, 2 X, 3 Y).
  void add_block(int row_kind, int column_kind, const Eigen::MatrixXd& block,
                 Eigen::MatrixXd& matrix) const;
  // Adds the symmetric coupling of the profile's x with the trajectory: `with_x` in the
  // (profile x, trajectory X) block, `with_y` in (profile x, trajectory Y), and their transposes.
  void add_profile_trajectory_coupling(const Eigen::MatrixXd& with_x, const Eigen::MatrixXd& with_y,
                                       Eigen::MatrixXd& matrix) const;
  void add_vector(int kind, const Eigen::VectorXd& values,
                  Eigen::Ref<Eigen::VectorXd>& vector) const;

  SwungLayout layout_;
  Split rest_;             // q_r by kind (zero without a rest shape)
  bool has_rest_ = false;  // set_rest called: the exact tangent subtracts the rest cross block
  double alpha_ = 1.0;
  double length_v_ = 0.0;                           // integral dv
  std::array<Eigen::MatrixXd, 3> profile_gram_;     // A_k, m by m
  std::array<Eigen::MatrixXd, 3> trajectory_gram_;  // B_l, n by n
  double mu_ = 0.0;
  double gamma_ = 0.0;
  std::array<double, 6> k_{};  // k_Q, Q = 1..5
};

}  // namespace dnurbs
