#pragma once
// Point constraints (Terzopoulos 2003, eqs. 1.39-1.40): a material point held at a target, two
// material points of two models joined (ball joint), and a hinge made of two ball joints. They work
// on any Model through x(u), L(u) and Ldot(u) qd, so D-NURBS surface points, superquadric points
// and grid nodes are all constrained the same way.

#include <memory>
#include <string>

#include "dnurbs/constraints/constraint.h"
#include "dnurbs/constraints/target_trajectory.h"

namespace dnurbs {

/// C = x_model(u) - target(t) (3 rows). C_q = L(u); sigma = xddot_target - Ldot qd.
class PointTargetConstraint : public Constraint {
 public:
  PointTargetConstraint(int model, const Eigen::Vector2d& u, TargetTrajectory target);
  std::unique_ptr<Constraint> clone() const override;
  int row_count() const override { return 3; }
  std::string description() const override;
  void check(const System& system) const override;
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                ConstraintRows& rows) const override;

  int model() const { return model_; }
  const Eigen::Vector2d& parameter() const { return u_; }
  const TargetTrajectory& target() const { return target_; }

 private:
  int model_;
  Eigen::Vector2d u_;
  TargetTrajectory target_;
};

/// Ball joint: C = x_a(u_a) - x_b(u_b) (3 rows). C_q = [L_a, -L_b];
/// sigma = -(Ldot_a qd_a - Ldot_b qd_b). Both points may belong to the same model.
class PointToPointConstraint : public Constraint {
 public:
  PointToPointConstraint(int model_a, const Eigen::Vector2d& u_a, int model_b,
                         const Eigen::Vector2d& u_b);
  std::unique_ptr<Constraint> clone() const override;
  int row_count() const override { return 3; }
  std::string description() const override;
  void check(const System& system) const override;
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                ConstraintRows& rows) const override;

 private:
  int model_a_;
  Eigen::Vector2d u_a_;
  int model_b_;
  Eigen::Vector2d u_b_;
};

/// Hinge: two ball joints between pairs of material points on the hinge axis (6 rows; one
/// rotational freedom about the axis through both pairs remains).
class HingeConstraint : public Constraint {
 public:
  HingeConstraint(int model_a, const Eigen::Vector2d& axis_a0, const Eigen::Vector2d& axis_a1,
                  int model_b, const Eigen::Vector2d& axis_b0, const Eigen::Vector2d& axis_b1);
  std::unique_ptr<Constraint> clone() const override;
  int row_count() const override { return 6; }
  std::string description() const override;
  void check(const System& system) const override;
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                ConstraintRows& rows) const override;

 private:
  PointToPointConstraint first_;
  PointToPointConstraint second_;
};

/// A control point of a D-NURBS model held at a fixed position by a multiplier (3 rows, linear:
/// C = P_i - P_target, sigma = 0). Prefer DNurbsModel::fix_control_point (elimination) for
/// control points that never move; this form lets a Baumgarte-stabilized constraint pull a
/// control point to a new place.
class ControlPointConstraint : public Constraint {
 public:
  ControlPointConstraint(int model, int control_point, const Eigen::Vector3d& target);
  std::unique_ptr<Constraint> clone() const override;
  int row_count() const override { return 3; }
  std::string description() const override;
  void check(const System& system) const override;
  void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                ConstraintRows& rows) const override;

 private:
  int model_;
  int control_point_;
  Eigen::Vector3d target_;
};

}  // namespace dnurbs
