#pragma once
// The tangents S_u, S_v of a swung surface with their Jacobians, rates and velocity-product
// terms (Model::tangent_kinematics), for constraints on the surface's orientation (a held
// normal, constraints/surface_constraints.h). With S = (alpha p_x t, p_z) (Qin & Terzopoulos,
// Dynamic NURBS swung surfaces for physics-based shape design, CAD 27(2) 1995)
//   S_u = (alpha p_x' t, p_z'),   S_v = (alpha p_x t', 0),
// bilinear in the two curves, so J_u = dS_u/dq and J_v depend on q and Jdot_u qd, Jdot_v qd are
// non-zero even for fixed weights.

#include <array>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/nurbs/swung_jacobian.h"

namespace dnurbs {

/// Fills `tangents` from a swung Jacobian of order >= 1 at one parameter (`jacobian`), the
/// velocity vector qd (size #coordinates of the layout the Jacobian was built with) and the
/// velocity-product terms of order >= 1 at that parameter (`rates`, swung_jacobian_rate):
/// su, sv = S_u, S_v; columns = the distinct coordinates of the Jacobian in ascending order
/// (a coordinate listed twice, as a periodic curve's wrapped control point can be, has its
/// columns summed); ju, jv = those columns of dS_u/dq and dS_v/dq (3 by #columns);
/// su_rate = J_u qd, sv_rate = J_v qd; su_bias = Jdot_u qd = rates[kU], sv_bias = rates[kV].
/// Throws Error if the Jacobian's order is below 1.
void swung_tangent_kinematics(const SwungJacobian& jacobian, const ConstVectorRef& qd,
                              const std::array<Eigen::Vector3d, 6>& rates,
                              TangentKinematics& tangents);

}  // namespace dnurbs
