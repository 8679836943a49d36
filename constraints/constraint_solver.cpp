#include "dnurbs/constraints/constraint_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Relative size below which an eigenvalue of S counts as zero: S's entries carry the rounding of
// m back-substitutions, about 1e-16 cond(A) |S|, far below it.
constexpr double kRankTolerance = 1e-10;
// A constraint is "involved" in a singular direction if one of its rows has at least this share
// of the (unit) null vector.
constexpr double kInvolvementThreshold = 1e-3;

bool same_matrix(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) {
    return false;
  }
  for (int column = 0; column < a.outerSize(); ++column) {
    SparseMatrix::InnerIterator ia(a, column);
    SparseMatrix::InnerIterator ib(b, column);
    for (; ia && ib; ++ia, ++ib) {
      if (ia.row() != ib.row() || ia.value() != ib.value()) {
        return false;
      }
    }
    if (ia || ib) {
      return false;
    }
  }
  return true;
}

}  // namespace

int ConstraintSolver::add(const System& system, std::unique_ptr<Constraint> constraint,
                          BaumgarteParameters parameters) {
  if (!constraint) {
    throw make_error("constraint solver: cannot add an empty constraint");
  }
  if (!std::isfinite(parameters.alpha) || parameters.alpha < 0.0 ||
      !std::isfinite(parameters.beta)) {
    throw make_error("Baumgarte alpha ", parameters.alpha, " and beta ", parameters.beta,
                     " must be finite with alpha >= 0");
  }
  if (parameters.beta < 0.0) {
    parameters.beta = parameters.alpha;
  }
  constraint->check(system);
  Entry entry;
  entry.first_row = rows_;
  rows_ += constraint->row_count();
  entry.constraint = std::move(constraint);
  entry.parameters = parameters;
  constraints_.push_back(std::move(entry));
  cache_valid_ = false;
  return static_cast<int>(constraints_.size()) - 1;
}

int ConstraintSolver::add(const System& system, const Constraint& constraint,
                          BaumgarteParameters parameters) {
  return add(system, constraint.clone(), parameters);
}

void ConstraintSolver::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                double time, Evaluation& evaluation) const {
  evaluation.value.setZero(rows_);
  evaluation.rate.setZero(rows_);
  evaluation.sigma.setZero(rows_);
  std::vector<Eigen::Triplet<double>> triplets;
  ConstraintRows rows;
  rows.value = &evaluation.value;
  rows.rate = &evaluation.rate;
  rows.sigma = &evaluation.sigma;
  rows.jacobian = &triplets;
  for (const Entry& entry : constraints_) {
    rows.row = entry.first_row;
    entry.constraint->evaluate(system, q, qd, time, rows);
  }
  evaluation.jacobian.resize(rows_, system.velocity_count());
  evaluation.jacobian.setFromTriplets(triplets.begin(), triplets.end());
}

void ConstraintSolver::step(Integrator& integrator, System& system, double dt) {
  if (constraints_.empty()) {
    integrator.step(system, dt);
    return;
  }
  integrator.set_solve_hook([this, &system](const StepSystem& step_system, Eigen::VectorXd& delta) {
    solve_iteration(system, step_system, delta);
  });
  try {
    integrator.step(system, dt);
  } catch (...) {
    integrator.set_solve_hook(nullptr);
    throw;
  }
  integrator.set_solve_hook(nullptr);
  if (report_.rank_deficient) {
    ++rank_deficient_steps_;
  }
  if (projection_) {
    project(system);
  }
}

void ConstraintSolver::set_projection(bool enabled, double tolerance, int iterations) {
  if (!std::isfinite(tolerance) || tolerance < 0.0 || iterations < 1) {
    throw make_error(
        "constraint projection needs a tolerance >= 0 and at least one iteration, got ", tolerance,
        " and ", iterations);
  }
  projection_ = enabled;
  projection_tolerance_ = tolerance;
  projection_iterations_ = iterations;
}

void ConstraintSolver::project(System& system) const {
  // Minimum-norm corrections with the pseudo-inverse of C_q C_q^T (rank-deficient rows allowed);
  // fixed coordinates are not moved.
  const int n = system.velocity_count();
  Eigen::VectorXd keep = Eigen::VectorXd::Ones(n);
  for (const int index : system.fixed_coordinates()) {
    keep[index] = 0.0;
  }
  const auto correction = [&](const SparseMatrix& jacobian, const Eigen::VectorXd& residual) {
    const SparseMatrix C_q = jacobian * keep.asDiagonal();
    const Eigen::MatrixXd gram = Eigen::MatrixXd(C_q * C_q.transpose());
    const Eigen::VectorXd multipliers = gram.completeOrthogonalDecomposition().solve(residual);
    return Eigen::VectorXd(C_q.transpose() * multipliers);
  };
  Evaluation evaluation;
  Eigen::VectorXd q = system.coordinates();
  Eigen::VectorXd qd = system.velocities();
  Eigen::VectorXd moved(q.size());
  for (int iteration = 0; iteration < projection_iterations_; ++iteration) {
    evaluate(system, q, qd, system.time(), evaluation);
    if (evaluation.value.cwiseAbs().maxCoeff() <= projection_tolerance_) {
      break;
    }
    const Eigen::VectorXd step = -correction(evaluation.jacobian, evaluation.value);
    system.advance_coordinates(q, step, moved);
    q = moved;
  }
  evaluate(system, q, qd, system.time(), evaluation);
  qd -= correction(evaluation.jacobian, evaluation.rate);
  if (!q.allFinite() || !qd.allFinite()) {
    return;  // keep the unprojected (finite) state rather than a broken one
  }
  system.set_state(q, qd, system.time());
}

void ConstraintSolver::solve_iteration(const System& system, const StepSystem& step,
                                       Eigen::VectorXd& delta) {
  const int n = system.velocity_count();
  evaluate(system, *step.predicted_coordinates, *step.predicted_velocities, step.state_time,
           evaluation_);
  SparseMatrix& C_q = evaluation_.jacobian;
  // Fixed coordinates never move: their columns take no part in the solve.
  if (!step.fixed_coordinates->empty()) {
    Eigen::VectorXd keep = Eigen::VectorXd::Ones(n);
    for (const int index : *step.fixed_coordinates) {
      keep[index] = 0.0;
    }
    C_q = C_q * keep.asDiagonal();
    C_q.prune(0.0);
  }

  // Right-hand side of the Baumgarte rows (Terzopoulos 2003, eq. 1.40), scaled for the end of the
  // step.
  Eigen::VectorXd target(rows_);
  const Eigen::VectorXd current = C_q * *step.acceleration;
  for (const Entry& entry : constraints_) {
    const double alpha = entry.parameters.alpha;
    const double beta = entry.parameters.beta;
    const double scale =
        1.0 + 2.0 * alpha * step.velocity_coefficient + beta * beta * step.position_coefficient;
    const int first = entry.first_row;
    const int count = entry.constraint->row_count();
    target.segment(first, count) =
        (evaluation_.sigma.segment(first, count) -
         2.0 * alpha * evaluation_.rate.segment(first, count) -
         beta * beta * evaluation_.value.segment(first, count) - current.segment(first, count)) /
        scale;
  }

  // Schur complement S = C_q A^-1 C_q^T, rebuilt only when C_q or A's factorization changed.
  const std::uint64_t factorization = step.factorization_serial;
  if (!cache_valid_ || factorization != cached_factorization_ ||
      !same_matrix(C_q, cached_jacobian_)) {
    solved_jacobian_.resize(n, rows_);
    const SparseMatrix C_q_transpose = C_q.transpose();
    Eigen::VectorXd column(n);
    Eigen::VectorXd solution(n);
    for (int row = 0; row < rows_; ++row) {
      column = C_q_transpose.col(row);
      step.solve(column, solution);
      solved_jacobian_.col(row) = solution;
    }
    Eigen::MatrixXd schur = C_q * solved_jacobian_;
    schur = 0.5 * (schur + schur.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(schur);
    const Eigen::VectorXd& values = eigen.eigenvalues();
    const double largest = values.cwiseAbs().maxCoeff();
    const double tolerance = kRankTolerance * std::max(largest, 1e-300);
    Eigen::VectorXd inverse_values = Eigen::VectorXd::Zero(rows_);
    ConstraintReport report;
    report.row_count = rows_;
    std::vector<bool> involved(constraints_.size(), false);
    for (int k = 0; k < rows_; ++k) {
      if (values[k] > tolerance) {
        inverse_values[k] = 1.0 / values[k];
        ++report.rank;
        continue;
      }
      for (size_t c = 0; c < constraints_.size(); ++c) {
        const int first = constraints_[c].first_row;
        const int count = constraints_[c].constraint->row_count();
        if (eigen.eigenvectors().col(k).segment(first, count).cwiseAbs().maxCoeff() >
            kInvolvementThreshold) {
          involved[c] = true;
        }
      }
    }
    report.rank_deficient = report.rank < rows_;
    for (size_t c = 0; c < constraints_.size(); ++c) {
      if (involved[c]) {
        report.involved.push_back(static_cast<int>(c));
      }
    }
    schur_pseudo_inverse_ =
        eigen.eigenvectors() * inverse_values.asDiagonal() * eigen.eigenvectors().transpose();
    cached_report_ = report;
    cached_jacobian_ = C_q;
    cached_factorization_ = factorization;
    cache_valid_ = true;
  }

  // lambda = S^+ (C_q A^-1 b - r), da = A^-1 b - X lambda.
  Eigen::VectorXd unconstrained(n);
  step.solve(*step.rhs, unconstrained);
  multipliers_ = schur_pseudo_inverse_ * (C_q * unconstrained - target);
  delta = unconstrained - solved_jacobian_ * multipliers_;
  constraint_force_ = -(C_q.transpose() * multipliers_);

  report_ = cached_report_;
  report_.residual = (C_q * delta - target).norm();
  if (report_.rank_deficient) {
    std::ostringstream message;
    message << "constraint rows are rank deficient (rank " << report_.rank << " of "
            << report_.row_count << "); least-squares step, residual " << report_.residual
            << "; involved:";
    for (const int c : report_.involved) {
      message << " [" << c << "] " << constraints_[static_cast<size_t>(c)].constraint->description()
              << ";";
    }
    report_.message = message.str();
  } else {
    report_.message.clear();
  }
}

Eigen::VectorXd ConstraintSolver::violations(const System& system) const {
  Evaluation evaluation;
  evaluate(system, system.coordinates(), system.velocities(), system.time(), evaluation);
  Eigen::VectorXd result(constraint_count());
  for (size_t c = 0; c < constraints_.size(); ++c) {
    result[static_cast<Eigen::Index>(c)] =
        evaluation.value.segment(constraints_[c].first_row, constraints_[c].constraint->row_count())
            .norm();
  }
  return result;
}

double ConstraintSolver::max_violation(const System& system) const {
  return constraints_.empty() ? 0.0 : violations(system).maxCoeff();
}

}  // namespace dnurbs
