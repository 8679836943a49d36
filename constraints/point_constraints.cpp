#include "dnurbs/constraints/point_constraints.h"

#include <sstream>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

std::string point_name(int model, const Eigen::Vector2d& u) {
  std::ostringstream text;
  text << "model " << model << " at (" << u.x() << ", " << u.y() << ")";
  return text.str();
}

}  // namespace

// ---------------------------------------------------------------------------------------------

PointTargetConstraint::PointTargetConstraint(int model, const Eigen::Vector2d& u,
                                             TargetTrajectory target)
    : model_(model), u_(u), target_(std::move(target)) {}

std::unique_ptr<Constraint> PointTargetConstraint::clone() const {
  return std::make_unique<PointTargetConstraint>(*this);
}

std::string PointTargetConstraint::description() const {
  return "point of " + point_name(model_, u_) + " held at a target";
}

void PointTargetConstraint::check(const System& system) const {
  check_material_point(system, model_, u_, "point target constraint");
}

void PointTargetConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                     double time, ConstraintRows& rows) const {
  const ModelView view = model_view(system, model_, q, qd);
  const SparseMatrix L = view.model.position_jacobian(view.q, u_);
  // Terzopoulos 2003, eq. 1.40: C = x - x_target, Cdot = L qd - xdot_target,
  // sigma = -C_tt - (C_q qd)_q qd = xddot_target - Ldot qd.
  rows.value->segment<3>(rows.row) = view.model.position(view.q, u_) - target_.position(time);
  rows.rate->segment<3>(rows.row) = L * view.qd - target_.velocity(time);
  rows.sigma->segment<3>(rows.row) =
      target_.acceleration(time) - view.model.jacobian_rate_times_velocity(view.q, view.qd, u_);
  append_jacobian_block(L, 0, view.velocity_offset, 1.0, rows);
}

// ---------------------------------------------------------------------------------------------

PointToPointConstraint::PointToPointConstraint(int model_a, const Eigen::Vector2d& u_a, int model_b,
                                               const Eigen::Vector2d& u_b)
    : model_a_(model_a), u_a_(u_a), model_b_(model_b), u_b_(u_b) {}

std::unique_ptr<Constraint> PointToPointConstraint::clone() const {
  return std::make_unique<PointToPointConstraint>(*this);
}

std::string PointToPointConstraint::description() const {
  return "ball joint between " + point_name(model_a_, u_a_) + " and " + point_name(model_b_, u_b_);
}

void PointToPointConstraint::check(const System& system) const {
  check_material_point(system, model_a_, u_a_, "ball joint");
  check_material_point(system, model_b_, u_b_, "ball joint");
  if (model_a_ == model_b_ && u_a_ == u_b_) {
    throw make_error("ball joint joins ", point_name(model_a_, u_a_), " to itself");
  }
}

void PointToPointConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                      double /*time*/, ConstraintRows& rows) const {
  const ModelView a = model_view(system, model_a_, q, qd);
  const ModelView b = model_view(system, model_b_, q, qd);
  const SparseMatrix L_a = a.model.position_jacobian(a.q, u_a_);
  const SparseMatrix L_b = b.model.position_jacobian(b.q, u_b_);
  rows.value->segment<3>(rows.row) = a.model.position(a.q, u_a_) - b.model.position(b.q, u_b_);
  rows.rate->segment<3>(rows.row) = L_a * a.qd - L_b * b.qd;
  rows.sigma->segment<3>(rows.row) = b.model.jacobian_rate_times_velocity(b.q, b.qd, u_b_) -
                                     a.model.jacobian_rate_times_velocity(a.q, a.qd, u_a_);
  append_jacobian_block(L_a, 0, a.velocity_offset, 1.0, rows);
  append_jacobian_block(L_b, 0, b.velocity_offset, -1.0, rows);
}

// ---------------------------------------------------------------------------------------------

HingeConstraint::HingeConstraint(int model_a, const Eigen::Vector2d& axis_a0,
                                 const Eigen::Vector2d& axis_a1, int model_b,
                                 const Eigen::Vector2d& axis_b0, const Eigen::Vector2d& axis_b1)
    : first_(model_a, axis_a0, model_b, axis_b0), second_(model_a, axis_a1, model_b, axis_b1) {}

std::unique_ptr<Constraint> HingeConstraint::clone() const {
  return std::make_unique<HingeConstraint>(*this);
}

std::string HingeConstraint::description() const {
  return "hinge: " + first_.description() + "; " + second_.description();
}

void HingeConstraint::check(const System& system) const {
  first_.check(system);
  second_.check(system);
}

void HingeConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                               double time, ConstraintRows& rows) const {
  first_.evaluate(system, q, qd, time, rows);
  ConstraintRows shifted = rows;
  shifted.row += 3;
  second_.evaluate(system, q, qd, time, shifted);
}

// ---------------------------------------------------------------------------------------------

ControlPointConstraint::ControlPointConstraint(int model, int control_point,
                                               const Eigen::Vector3d& target)
    : model_(model), control_point_(control_point), target_(target) {}

std::unique_ptr<Constraint> ControlPointConstraint::clone() const {
  return std::make_unique<ControlPointConstraint>(*this);
}

std::string ControlPointConstraint::description() const {
  std::ostringstream text;
  text << "control point " << control_point_ << " of model " << model_ << " held at a target";
  return text.str();
}

void ControlPointConstraint::check(const System& system) const {
  if (model_ < 0 || model_ >= system.model_count()) {
    throw make_error("control point constraint: model index ", model_, " is out of range");
  }
  if (!target_.allFinite()) {
    throw make_error("control point constraint: target is not finite");
  }
  system.model(model_).control_point_offset(control_point_);  // throws for a bad index
}

void ControlPointConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                      double /*time*/, ConstraintRows& rows) const {
  const ModelView view = model_view(system, model_, q, qd);
  const int offset = view.model.control_point_offset(control_point_);
  // Velocity and coordinate layouts of D-NURBS models agree, so the offset serves both.
  rows.value->segment<3>(rows.row) = view.q.segment<3>(offset) - target_;
  rows.rate->segment<3>(rows.row) = view.qd.segment<3>(offset);
  rows.sigma->segment<3>(rows.row).setZero();
  for (int c = 0; c < 3; ++c) {
    rows.jacobian->emplace_back(rows.row + c, view.velocity_offset + offset + c, 1.0);
  }
}

}  // namespace dnurbs
