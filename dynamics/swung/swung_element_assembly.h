#pragma once
// Assembly of the mass, damping and tangent stiffness matrices of a swung D-NURBS surface
// (Qin & Terzopoulos, Dynamic NURBS swung surfaces for physics-based shape design, CAD 27(2)
// 1995; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations,
// eqs. 1.20 and 1.25) element by element: an element is one non-empty span of the profile times
// one of the trajectory, whose Gauss points all share the same active coordinates.
//
// Per element the weighted Jacobians of all its Gauss points are stacked, so each J^T J sum is
// one symmetric rank-k update, the cross-curve second derivatives one matrix product, and each
// curve's own second derivatives (free weights) one evaluation per Gauss point of that curve.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/swung/swung_quadrature.h"
#include "dnurbs/nurbs/swung_jacobian.h"

namespace dnurbs {

/// Element-by-element assembly of dense M, D and K for one state. Holds work buffers sized once
/// for the element's columns and Gauss points; use one per assembly (not thread-safe).
class SwungElementAssembly {
 public:
  /// `geometric_stiffness` adds sum_c (S^Q_c - S^Q_c(q_r)) d^2 S^Q_c / dq^2 to the Gauss-Newton
  /// part of K, with the rest shape `rest` at the Gauss points (S^Q(q_r) = 0 when it is empty).
  /// `quadrature` and `rest` must outlive the assembly.
  SwungElementAssembly(const SwungQuadrature& quadrature, const SwungRestPoints& rest,
                       const SwungLayout& layout, double alpha, int profile_degree,
                       int trajectory_degree, bool geometric_stiffness);

  /// Adds, over every Gauss point, to the dense #coordinates square matrices
  ///   mass += integral mu J^T J,  damping += integral gamma J^T J (only if the material has
  ///   damping; `damping` may be empty otherwise),
  ///   stiffness += integral sum_Q k_Q (J_Q^T J_Q [+ sum_c (S^Q_c - S^Q_c(q_r)) d^2 S^Q_c / dq^2]),
  /// from the rational samples of both curves at their Gauss points (SwungQuadrature::sample).
  void assemble(const std::vector<PlanarCurveSample>& profile,
                const std::vector<PlanarCurveSample>& trajectory, Eigen::MatrixXd& mass,
                Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness);

 private:
  // Adds Gauss point pair (i, j) to the element's stacks.
  void add_point(const PlanarCurveSample& profile, const PlanarCurveSample& trajectory, int i,
                 int j);
  // Forms the element matrices from the stacks of element (su, sv) and scatters them.
  void finish(const std::vector<PlanarCurveSample>& profile,
              const std::vector<PlanarCurveSample>& trajectory, int su, int sv,
              Eigen::MatrixXd& mass, Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness);

  const SwungQuadrature& quadrature_;
  const SwungRestPoints& rest_;
  SwungLayout layout_;
  double alpha_ = 1.0;
  bool geometric_stiffness_ = true;
  int order_ = 0;            // derivative order of the stiffness
  int profile_columns_ = 0;  // per (p + 1)
  int columns_ = 0;          // per (p + 1) + per (q + 1)
  SwungJacobian jacobian_;
  SwungHessianTerms terms_;
  // Stacks of the element's weighted Jacobians: sqrt(w mu) J, sqrt(w gamma) J, sqrt(w k_Q) J_Q,
  // and the rows of the cross-curve Hessian factors; `*_rows_` rows used.
  Eigen::MatrixXd mass_stack_, damping_stack_, stiffness_stack_;
  Eigen::MatrixXd profile_factors_, trajectory_factors_;
  int mass_rows_ = 0;
  int stiffness_rows_ = 0;
  int factor_rows_ = 0;
  // Free weights: the weights mu of each curve's own second derivatives, summed over the
  // element's points and quantities, per Gauss point of the curve and derivative order.
  std::vector<Eigen::Matrix<double, 2, 3>> profile_weights_, trajectory_weights_;
  // Element matrices: upper triangles of the J^T J sums, the full second-derivative part.
  Eigen::MatrixXd mass_, damping_, gram_, hessian_;
};

}  // namespace dnurbs
