#pragma once
// Static equilibrium of a linear system: K q = f on the free coordinates, the fixed ones held at
// their current values (Terzopoulos 2003, eq. 1.24 with qdd = qd = 0 and g = 0).

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// Solves K_ff q_f = f_f - K_fc q_c for the free coordinates q_f, f the applied forces at the
/// system's time and current state (state-dependent forces are evaluated once, at the current
/// state), and sets the result with zero velocity. Springs (System::add_spring) are exact: K
/// includes their k L^T L and f their k L^T target. Only for constant-matrix systems (throws
/// Error otherwise). Throws Error if K_ff is singular (e.g. nothing is fixed, so a rigid
/// translation costs no energy).
void solve_static_equilibrium(System& system);

}  // namespace dnurbs
