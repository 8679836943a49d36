#pragma once
// Applied forces for System::add_force. Every generalized force goes through L^T (Terzopoulos 2003,
// below eq 1.26: f_q = integral J^T f(u, t) du): a point force f at u gives L(u)^T f, a force
// density gives integral L^T f. Forces that depend on the state are explicit in the integrators
// (their derivatives are not in the effective matrix); springs added with System::add_spring
// (dynamics/core/spring.h) are the implicit alternative to spring_force. VectorOfTime and
// ScalarOfTime are declared in dynamics/core/spring.h.

#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// The force f(t) acting at the material point u: L(u)^T f(t).
Force point_force(const Eigen::Vector2d& u, VectorOfTime force);
Force point_force(const Eigen::Vector2d& u, const Eigen::Vector3d& force);
/// On a curve: the material point is the parameter u alone (the same force as at (u, 0)).
Force point_force(double u, VectorOfTime force);
Force point_force(double u, const Eigen::Vector3d& force);

/// An explicit spring of stiffness k from the material point u to a target that moves in time:
/// L(u)^T k (target(t) - x(u)), evaluated at the state like any force, its stiffness not in the
/// step matrix (stable only for k small against the mass at the integrator's dt). Prefer
/// System::add_spring(model, mouse_spring(...)), which is implicit. Throws Error if k is negative
/// or not finite.
Force spring_force(const Eigen::Vector2d& u, VectorOfTime target, double stiffness);
/// On a curve: spring_force at the parameter u alone (as at (u, 0)).
Force spring_force(double u, VectorOfTime target, double stiffness);

/// The force f(t) added directly to the position coordinates of each listed control point
/// (Model::control_point_offset; indices are checked when the force is first applied).
Force control_point_force(std::vector<int> control_points, VectorOfTime force);
/// The same with a constant force f.
Force control_point_force(std::vector<int> control_points, const Eigen::Vector3d& force);

/// A generalized force value(t) added directly to each listed velocity-space coordinate (e.g.
/// a D-NURBS weight, DNurbsModel::weight_offset).
Force coordinate_force(std::vector<int> coordinates, ScalarOfTime value);

/// Gravity: the density mu(u) g per unit parametric measure, integral L^T mu g.
Force gravity(const Eigen::Vector3d& acceleration);

/// Pressure p(t) along the surface normal (inflation): force per unit area p n, i.e.
/// p (x_u x x_v) per unit parametric area; integral L^T p (x_u x x_v) du dv. For a closed
/// surface this is p dV/dq (V the enclosed volume). Curves have x_v = 0: no force.
Force pressure(ScalarOfTime pressure);
Force pressure(double pressure);

/// Wind: the viscous fluid force of Terzopoulos, Platt, Barr & Fleischer, "Elastically
/// deformable models", SIGGRAPH 1987, section 5 (the flag in wind and the rug of Terzopoulos,
/// "Deformable Models: Classic, Topology-Adaptive and Generalized Formulations", figure 1). Per
/// unit surface area
///
///   f = drag (n . (v_wind(t) - xdot)) n,      n = x_u x x_v / |x_u x x_v|, xdot = L(u) qd,
///
/// so per unit parametric area drag (N . (v_wind - xdot)) N / |N| with N = x_u x x_v, and the
/// generalized force is integral L^T f |N| du dv by the model's quadrature rule (Gauss points of
/// D-NURBS, node areas h^2 of grid surfaces). Only the velocity along the normal is resisted: a
/// sheet parallel to the wind or moving with it feels none. Curves (x_v = 0) and degenerate
/// points (N = 0) get no force. Units: drag is force per unit area per unit velocity (mass per
/// unit area per unit time), v_wind a velocity. The force is explicit like every applied force:
/// its velocity part -drag (n . xdot) n is a damping that is not in the step matrix, so it is
/// stable only while drag dt is small against the mass per unit area (about drag dt < 2 mu).
/// Throws Error naming the value if drag is negative or not finite, or if there is no velocity
/// function.
Force wind(VectorOfTime wind_velocity, double drag);
/// The same with a constant wind velocity (Error naming a non-finite one).
Force wind(const Eigen::Vector3d& wind_velocity, double drag);

/// `force` while start <= t < end, nothing outside that window.
Force windowed(Force force, double start, double end);

}  // namespace dnurbs
