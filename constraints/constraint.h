#pragma once
// The holonomic constraint interface (Terzopoulos 2003, eqs. 1.39-1.40; DESIGN.md, "Constraints"):
// C(q, t) = 0 with its sparse Jacobian C_q, its rate Cdot = C_q qd + C_t and the
// velocity-product term sigma = -C_tt - (C_q qd)_q qd - 2 C_qt qd, so that the constrained
// acceleration satisfies C_q qdd = sigma - 2 alpha Cdot - beta^2 C.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// Where a constraint writes its rows: entries of C, Cdot and sigma at `row` .. row + rows - 1,
/// and the non-zeros of C_q (columns in the System's velocity space) as triplets.
struct ConstraintRows {
  int row = 0;
  Eigen::VectorXd* value = nullptr;                         ///< C
  Eigen::VectorXd* rate = nullptr;                          ///< Cdot = C_q qd + C_t
  Eigen::VectorXd* sigma = nullptr;                         ///< -C_tt - (C_q qd)_q qd - 2 C_qt qd
  std::vector<Eigen::Triplet<double>>* jacobian = nullptr;  ///< C_q
};

/// A constraint between (or inside) the models of a System. Constraints are values: clone().
class Constraint {
 public:
  virtual ~Constraint() = default;
  virtual std::unique_ptr<Constraint> clone() const = 0;
  /// Number of scalar equations.
  virtual int row_count() const = 0;
  /// A short description for reports ("point of model 0 at (0.5, 0.5) held at a target").
  virtual std::string description() const = 0;
  /// Throws Error naming the problem if the constraint does not fit `system` (a model index out
  /// of range, a parameter outside the model's domain, a model of the wrong kind).
  virtual void check(const System& system) const = 0;
  /// Evaluates C, Cdot, sigma and C_q at stacked coordinates q, velocities qd and time t.
  virtual void evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd, double time,
                        ConstraintRows& rows) const = 0;

 protected:
  Constraint() = default;
  Constraint(const Constraint&) = default;
  Constraint& operator=(const Constraint&) = default;
};

/// Helpers for constraint implementations: a model's coordinates, velocities and the offset of
/// its velocity-space columns inside the System's stacked vectors.
struct ModelView {
  const Model& model;
  ConstVectorRef q;
  ConstVectorRef qd;
  int velocity_offset;
};
ModelView model_view(const System& system, int model, ConstVectorRef q, ConstVectorRef qd);

/// Appends `block` (rows by model velocities) shifted to (rows.row + row_offset, velocity_offset)
/// and multiplied by `scale` to rows.jacobian.
void append_jacobian_block(const SparseMatrix& block, int row_offset, int velocity_offset,
                           double scale, ConstraintRows& rows);

/// Throws Error if `model` is not a valid index of `system` or u is not finite.
void check_material_point(const System& system, int model, const Eigen::Vector2d& u,
                          const char* what);

}  // namespace dnurbs
