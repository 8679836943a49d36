#pragma once
// Implicit springs: the stiffness of every spring (System::add_spring, dynamics/core/spring.h)
// enters the step matrix of the integrators, so that no spring stiffness or time step makes a
// step of a linear model unstable (Newmark's average acceleration conserves the energy of model
// plus springs, implicit Euler never gains energy).
//
// A spring of stiffness k at the material point u pulls with f = k (target - x(u)), whose
// generalized force L(u)^T f (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and
// Generalized Formulations, below eq. 1.26) is linear in q where L does not depend on q. In the
// step of integrator.h, q = q_iter + c_K delta (c_K the position coefficient), so
//
//   (A + c_K k L^T L) delta = b + k L^T (target - x(q_iter, u)),
//
// exact for constant L and the Gauss-Newton linearization of the spring otherwise. For a model
// with the S (x) I_3 layout (fixed-weight D-NURBS, snakes) L = N(u)^T (x) I_3, N(u) the few
// non-zero basis functions at u, and the term is c_K k N N^T on the scalar matrix: rank one, with
// the x, y, z pulls as the three right-hand sides. Other blocks take the three rows l_r of L as
// three rank-one terms c_K k l_r^T l_r.
//
// The terms are kept on the factor of A by LowRankUpdate (core/low_rank_update.h: Woodbury's
// identity on the solve), so that adding, moving (a drag) or removing a spring costs one extra
// solve column, not a factorization. Their pulls are in LowRankUpdate's target form,
// t = (target - x(q_iter, u)) / c_K, in which the stiff spring's pull costs no digits; when a
// solve hook (constraints) needs A^{-1} as a linear map the targets are cleared and the pull goes
// into b instead.
//
// Stability. With the springs in A, a linear model with springs of fixed parameter is a linear
// time-invariant system between changes of target: Newmark's average acceleration conserves its
// energy and implicit Euler dissipates it, for any k and dt; a moving target (the usual drag: the
// grabbed material point pinned, the pointer moving) does work, as it should. A spring whose
// PARAMETER moves every step (the attachment sliding over the material) makes the step matrix
// time-varying. Implicit Euler stays stable: it damps the spring's own mode by about
// 1 / (omega dt)^2 per step (omega^2 = k N^T M^{-1} N). The average-acceleration rule leaves that
// mode ringing at the step frequency when omega dt >> 1, and the attachment moving across the
// ringing bump does work of one sign every step: the motion grows geometrically (measured on a
// clamped 8 by 8 sheet whose spring slides 0.02 in u per step: displacements of 1e2 to 2e6 after
// 40 steps for k = 1e4 at dt = 0.1 and k = 1e6 at dt = 1/60 and 0.1, against 0.3 to 1.7 under
// implicit Euler). Neither restarting a_n from the new springs' force nor Newmark's numerical
// damping (gamma = 0.6) cured it (measured: growth as well). For sliding stiff springs use
// implicit Euler.

#include <array>
#include <span>
#include <vector>

#include "dnurbs/core/fixed_coordinates.h"
#include "dnurbs/core/low_rank_update.h"
#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// How the springs of a System enter the integrators' steps.
enum class SpringTreatment {
  /// Their stiffness on the factor of the step matrix as low-rank terms (Woodbury), pulls in
  /// target form: a moving spring costs one extra solve column. The default.
  kLowRank,
  /// Their stiffness summed into the step matrix, refactored whenever a spring is added, moved
  /// or removed; pulls in the right-hand side. The reference the low-rank form is tested against.
  kRefactor,
  /// Their forces evaluated at the iterate only, stiffness not in the step matrix (as applied
  /// forces, and as every spring before implicit springs): unstable for stiff springs.
  kExplicit,
};

/// The spring terms on one diagonal block of the step matrix (one model's free unknowns: nodes
/// for a block with the S (x) I_3 layout, velocities otherwise). Kept between steps so that a
/// spring whose parameter and stiffness stay keeps its terms (only its pull changes).
class BlockSprings {
 public:
  /// What one block looks like to its springs.
  struct Layout {
    int model = 0;                          ///< index of the block's model in the System
    int coordinate_offset = 0;              ///< of the model in stacked q
    bool kronecker = false;                 ///< unknowns are nodes (S (x) I_3 layout)
    const FreeCoordinates* free = nullptr;  ///< the block's free unknowns
  };

  /// Brings the terms up to date with the springs of the layout's model at time t and stacked
  /// coordinates q (the step's iterate), with stiffness c_K k: adds the terms of new springs,
  /// moves those whose parameter, stiffness or c_K changed, removes those of springs removed or
  /// off (k = 0), and sets every pull (target form when `target_form`, else none). `solver` is
  /// the block's LowRankUpdate, or nullptr when the terms are summed into the matrix (kRefactor).
  /// Returns true if the block's matrix changed (a term added, moved or removed). Throws Error if
  /// a model that declares the S (x) I_3 layout has a position Jacobian of another form.
  bool update(const System& system, const Layout& layout, double time, ConstVectorRef q,
              double position_coefficient, bool target_form, LowRankUpdate* solver);

  /// Adds every term's c_K k u u^T to `matrix` (free unknowns square; both triangles): the
  /// kRefactor form.
  void add_to_matrix(SparseMatrix& matrix) const;

  /// Terms held (one per spring on a node block, three per spring on a velocity block).
  int term_count() const;
  /// Forgets every term (after the solver was replaced).
  void clear() { entries_.clear(); }

 private:
  // One rank-one term stiffness u u^T: u's free unknowns and values, and its LowRankUpdate id.
  struct Term {
    std::vector<int> rows;
    std::vector<double> values;
    int id = -1;
  };
  // One spring's terms: one on a node block, three (the rows of L) on a velocity block.
  struct Entry {
    int spring = -1;
    double stiffness = 0.0;  // c_K k
    std::array<Term, 3> terms;
    int term_count = 0;
    bool seen = false;
  };

  // u and its pull (target - x) for each term of spring state `state` at q into scratch_.
  void evaluate(const System& system, const Layout& layout, ConstVectorRef q,
                const SpringState& state);

  std::vector<Entry> entries_;
  std::array<Term, 3> scratch_;
  Eigen::Vector3d gap_ = Eigen::Vector3d::Zero();  // target - x(q, u) of the evaluated spring
  int scratch_count_ = 0;
};

}  // namespace dnurbs
