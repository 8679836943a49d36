#pragma once
// Gauss quadrature of swung D-NURBS surfaces (Qin & Terzopoulos, Dynamic NURBS swung surfaces
// for physics-based shape design, CAD 27(2) 1995; Terzopoulos, Deformable Models: Classic,
// Topology-Adaptive and Generalized Formulations, eq. 1.25): Gauss-Legendre points over the
// non-empty spans of the profile (u) and of the trajectory (v), every pair (u_g, v_h) a point of
// the surface. The integrands depend on q through both curves, but each curve depends on one
// parameter only: the B-spline bases are cached at the Gauss points of their own direction once,
// and at a state each curve is made rational at its own points once (N_u + N_v curve samples),
// the N_u N_v surface Jacobians being products of those samples.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/quadrature_assembly.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/nurbs/swung_jacobian.h"
#include "dnurbs/nurbs/swung_surface.h"

namespace dnurbs {

/// Material values per quadrature point: [0] mu, [1] gamma, [1 + Q] the stiffness coefficient
/// k_Q of quantity Q = 1..5 (S_u, S_v, S_uu, S_uv, S_vv): a10, a01, b20, 2 b11, b02.
inline constexpr int kSwungMaterialStride = 7;

/// A rest shape q_r of a swung surface at the Gauss points: each curve's point and derivatives
/// c^(d), d = 0..2 (PlanarCurveSample::point, columns d) at every Gauss point of its own direction,
/// so that S^Q(q_r) at the pair (i, j) is swung_point_derivative(profile[i], trajectory[j],
/// alpha, Q), N_u + N_v small matrices for N_u N_v points. Empty: no rest shape.
struct SwungRestPoints {
  std::vector<Eigen::Matrix<double, 2, 3>> profile;     ///< N_u entries
  std::vector<Eigen::Matrix<double, 2, 3>> trajectory;  ///< N_v entries
  bool empty() const { return profile.empty(); }
  /// S^Q(q_r) at the point pair (i, j).
  Eigen::Vector3d derivative(int i, int j, double alpha, int quantity) const {
    return swung_point_derivative(profile[static_cast<size_t>(i)],
                                  trajectory[static_cast<size_t>(j)], alpha, quantity);
  }
};

/// The quadrature points of a swung surface and what is cached at them.
///
/// Caches (built once in the constructor, never invalidated: they depend only on the knots, the
/// rule and the material, which a model does not change): the B-spline basis N^(d), d = 0..2, of
/// each curve at each of its Gauss points, and the checked material values at every point pair.
class SwungQuadrature {
 public:
  SwungQuadrature() = default;
  /// `points_per_span` Gauss points per non-empty span in u, and `points_per_span_v` in v (each
  /// 1..kMaxGaussPoints). Throws Error naming the material value that is negative or not finite
  /// at a quadrature point.
  SwungQuadrature(const SwungSurface& surface, int points_per_span_u, int points_per_span_v,
                  const DNurbsSurfaceMaterial& material);

  /// Gauss points along the profile (N_u) and along the trajectory (N_v).
  int profile_point_count() const { return static_cast<int>(table_u_.parameter.size()); }
  int trajectory_point_count() const { return static_cast<int>(table_v_.parameter.size()); }
  /// Gauss points per non-empty span along u and v; point i of the profile lies in span
  /// i / profile_points_per_span() (likewise along v).
  int profile_points_per_span() const { return table_u_.points_per_span; }
  int trajectory_points_per_span() const { return table_v_.points_per_span; }
  /// Gauss weight (times half the span length) of profile point i and of trajectory point j.
  double profile_weight(int i) const { return table_u_.weight[static_cast<size_t>(i)]; }
  double trajectory_weight(int j) const { return table_v_.weight[static_cast<size_t>(j)]; }
  /// Gauss weight (times the span lengths) of the point pair (i, j).
  double weight(int i, int j) const {
    return table_u_.weight[static_cast<size_t>(i)] * table_v_.weight[static_cast<size_t>(j)];
  }
  Eigen::Vector2d parameter(int i, int j) const {
    return {table_u_.parameter[static_cast<size_t>(i)], table_v_.parameter[static_cast<size_t>(j)]};
  }
  /// kSwungMaterialStride material values of the point pair (i, j).
  const double* material(int i, int j) const {
    const int point = i * trajectory_point_count() + j;
    return &material_[static_cast<size_t>(point) * kSwungMaterialStride];
  }
  bool has_damping() const { return has_damping_; }
  /// True if the stiffness coefficient of quantity 1..5 is not the constant 0.
  bool has_stiffness(int quantity) const { return has_stiffness_[static_cast<size_t>(quantity)]; }
  /// Highest derivative order the stiffness needs (0, 1 or 2).
  int stiffness_order() const;

  /// The rational samples of both curves at all their Gauss points at coordinates q (layout
  /// `layout`, fixed weights from `profile_weights` / `trajectory_weights`).
  void sample(const SwungLayout& layout, const double* q, const double* profile_weights,
              const double* trajectory_weights, std::vector<PlanarCurveSample>& profile,
              std::vector<PlanarCurveSample>& trajectory) const;

 private:
  DirectionQuadrature table_u_;
  DirectionQuadrature table_v_;
  std::vector<PlanarCurveSample> profile_basis_;     // basis only, per u Gauss point
  std::vector<PlanarCurveSample> trajectory_basis_;  // basis only, per v Gauss point
  std::vector<double> material_;
  bool has_damping_ = false;
  std::array<bool, kQuantityCount> has_stiffness_{};
};

}  // namespace dnurbs
