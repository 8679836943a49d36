#pragma once
// Constraints on surfaces: a surface normal held parallel to a direction, and a curve glued onto
// a surface by samples.

#include <memory>
#include <string>
#include <vector>

#include "dnurbs/constraints/constraint.h"

namespace dnurbs {

/// The surface normal N = S_u x S_v at (u, v) held parallel (or anti-parallel) to `direction`:
/// C = [e1.N, e2.N] (2 rows) with e1, e2 an orthonormal basis of the plane normal to the
/// direction. C is measured in units of |S_u x S_v|. With dN = dS_u x S_v + S_u x dS_v,
///   C_q = e^T (-[S_v]x J_u + [S_u]x J_v),
///   sigma = -e.(2 Sdot_u x Sdot_v + (Jdot_u qd) x S_v + S_u x (Jdot_v qd)).
/// The model must give its tangent kinematics (Model::tangent_kinematics; D-NURBS surfaces do).
class SurfaceNormalConstraint : public Constraint {
 public:
  SurfaceNormalConstraint(int model, const Eigen::Vector2d& uv, const Eigen::Vector3d& direction);
  std::unique_ptr<Constraint> clone() const override;
  int row_count() const override { return 2; }
  std::string description() const override;
  void check(const System& system) const override;
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                ConstraintRows& rows) const override;

 private:
  int model_;
  Eigen::Vector2d uv_;
  Eigen::Vector3d direction_;
  Eigen::Vector3d e1_;
  Eigen::Vector3d e2_;
};

/// Ball joints that hold a curve model (`curve_model`) on a surface model (`surface_model`), both
/// with an exact NURBS shape (Model::exact_shape: D-NURBS curves and surfaces), at `sample_count`
/// curve parameters spread evenly over its domain. Each sample is joined to the surface point
/// nearest to it at the system's current state (closest point projection), so a curve drawn near
/// the surface is glued where it lies.
std::vector<std::unique_ptr<Constraint>> curve_on_surface_constraints(const System& system,
                                                                      int curve_model,
                                                                      int surface_model,
                                                                      int sample_count);

}  // namespace dnurbs
