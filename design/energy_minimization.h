#pragma once
// Energy-minimizing design (issue 9): the static shape of a System of D-NURBS models found by
// minimizing its elastic energy minus the work of the applied forces,
//
//   minimize  Pi(q) = sum_models E_i(q_i) - f . q      subject to  C(q) = 0,  w >= w_min,
//
// with NLopt. E_i = (1/2) q^T K(q) q is the model's potential_energy(); its gradient is
// -f_int(q) from add_internal_force (exact also for free weights, where K depends on q). f is the
// applied force evaluated once at the system's current state (as solve_static_equilibrium
// does). Deformable superquadrics take part with their translation, q_s and q_d (their
// orientation, a quaternion, is held: rotation velocities are not variables), so the same call
// minimizes the energy of a superquadric's q_s (its shape stiffness) under forces. C are the rows
// of a ConstraintSolver (any constraint type of the constraints layer, equalities with their
// analytic Jacobian C_q). Fixed coordinates keep their values and are not optimization variables;
// free weights of D-NURBS models are bounded below by the model's minimum weight.

#include <functional>
#include <string>

#include <Eigen/Core>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// The NLopt algorithm of a design problem.
enum class DesignAlgorithm {
  kSlsqp,                     ///< NLOPT_LD_SLSQP: dense quasi-Newton SQP, for small problems
  kAugmentedLagrangianLbfgs,  ///< NLOPT_AUGLAG_EQ with NLOPT_LD_LBFGS inside, for large ones
};

struct DesignSettings {
  DesignAlgorithm algorithm = DesignAlgorithm::kSlsqp;
  /// NLopt's relative tolerance on the variables (xtol_rel) and on Pi (ftol_rel); 0 disables.
  double variable_tolerance = 1e-14;
  double energy_tolerance = 0.0;
  /// Tolerance of every equality row |C_i| (NLopt's constraint tolerance).
  double constraint_tolerance = 1e-12;
  /// Most evaluations of Pi (NLopt's maxeval; > 0) and of the inner solver for AUGLAG_EQ.
  int max_evaluations = 5000;
  /// Wall-clock limit in seconds (0: none).
  double max_seconds = 0.0;
  /// Called after every evaluation of Pi with the evaluations so far and Pi there (progress
  /// reports; empty: none). It must not throw.
  std::function<void(int evaluations, double energy)> on_evaluation;
};

struct DesignResult {
  Eigen::VectorXd coordinates;        ///< stacked coordinates of the optimum (System order)
  int iterations = 0;                 ///< evaluations of Pi and its gradient
  double energy = 0.0;                ///< Pi at the optimum
  double constraint_violation = 0.0;  ///< max |C_i| at the optimum (0 without constraints)
  int status = 0;                     ///< nlopt::result (> 0 success, < 0 failure)
  std::string status_name;  ///< "XTOL_REACHED", "MAXEVAL_REACHED", "ROUNDOFF_LIMITED", ...
  bool converged() const { return status > 0; }
};

/// Pi(q) and its gradient dPi/dq (System velocity space) at stacked coordinates q, f the applied
/// forces at the current state (velocity space; the work of a velocity without a vector-space
/// coordinate, a superquadric's rotation, is left out). For the finite-difference check.
double design_energy(const System& system, const Eigen::VectorXd& applied_force,
                     const Eigen::VectorXd& q, Eigen::VectorXd* gradient);

/// Minimizes Pi over the free coordinates of `system`, starting at its current coordinates, with
/// the rows of `constraints` (may be null) as equalities. Does not change `system`; use
/// system.set_coordinates / set_state with the result. Throws Error for a model whose velocities
/// cannot be mapped to coordinates (sizes differ and it is not a DeformableSuperquadricModel),
/// if the settings are invalid, if the start
/// is not finite, or if NLopt fails outright (invalid arguments, out of memory); a run stopped
/// by a limit or by round-off is returned with its status.
DesignResult minimize_energy(const System& system, const ConstraintSolver* constraints,
                             const DesignSettings& settings = {});

}  // namespace dnurbs
