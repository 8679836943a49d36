#include "dnurbs/design/dnurbs_fitting.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>
#include <nlopt.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/nurbs/closest_point.h"

namespace dnurbs {
namespace {

void check_settings(const DNurbsFitSettings& settings) {
  if (!(settings.smoothness >= 0.0) || !std::isfinite(settings.smoothness)) {
    throw make_error("fit smoothness must be finite and >= 0 (it is ", settings.smoothness, ")");
  }
  if (settings.max_iterations < 1) {
    throw make_error("fit max_iterations must be >= 1 (it is ", settings.max_iterations, ")");
  }
  if (!(settings.parameter_tolerance >= 0.0)) {
    throw make_error("fit parameter_tolerance must be >= 0 (it is ", settings.parameter_tolerance,
                     ")");
  }
}

// One least-squares solve at fixed parameters: (A^T A + s K) q = A^T p on the free coordinates.
Eigen::VectorXd solve_least_squares(const DNurbsModel& model, const Eigen::VectorXd& q0,
                                    const Eigen::MatrixX3d& points,
                                    const Eigen::MatrixX2d& parameters, double smoothness) {
  const int n = model.coordinate_count();
  SparseMatrix normal(n, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const SparseMatrix L = model.position_jacobian(q0, parameters.row(k).transpose());
    normal += SparseMatrix(L.transpose() * L);
    rhs += L.transpose() * points.row(k).transpose();
  }
  if (smoothness > 0.0) {
    normal += smoothness * model.constant_matrices()->stiffness;
  }

  // Eliminate the fixed coordinates: H_ff q_f = b_f - H_fc q_c.
  std::vector<int> index(static_cast<size_t>(n), 0);
  for (const int fixed : model.fixed_coordinates()) {
    index[static_cast<size_t>(fixed)] = -1;
  }
  Eigen::VectorXd held = Eigen::VectorXd::Zero(n);
  std::vector<int> free;
  for (int i = 0; i < n; ++i) {
    if (index[static_cast<size_t>(i)] < 0) {
      held[i] = q0[i];
    } else {
      index[static_cast<size_t>(i)] = static_cast<int>(free.size());
      free.push_back(i);
    }
  }
  rhs.noalias() -= normal * held;
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index j = 0; j < normal.outerSize(); ++j) {
    const int fj = index[static_cast<size_t>(j)];
    if (fj < 0) {
      continue;
    }
    for (SparseMatrix::InnerIterator it(normal, j); it; ++it) {
      const int fi = index[static_cast<size_t>(it.row())];
      if (fi >= 0) {
        triplets.emplace_back(fi, fj, it.value());
      }
    }
  }
  const auto free_count = static_cast<int>(free.size());
  SparseMatrix reduced(free_count, free_count);
  reduced.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd rhs_free(free_count);
  for (int i = 0; i < free_count; ++i) {
    rhs_free[i] = rhs[free[static_cast<size_t>(i)]];
  }
  Eigen::SimplicialLDLT<SparseMatrix> solver(reduced);
  Eigen::VectorXd solution;
  if (solver.info() == Eigen::Success) {
    solution = solver.solve(rhs_free);
  }
  // LDLT of a singular PSD matrix may "succeed" with a zero pivot: check the residual too.
  const double scale = std::max(1.0, rhs_free.norm());
  if (solver.info() != Eigen::Success || !solution.allFinite() ||
      (reduced * solution - rhs_free).norm() > 1e-8 * scale) {
    throw make_error("the fitting normal matrix (", free_count, " coordinates, ", points.rows(),
                     " points) is singular: add points or smoothness");
  }
  Eigen::VectorXd q = q0;
  for (int i = 0; i < free_count; ++i) {
    q[free[static_cast<size_t>(i)]] = solution[i];
  }
  return q;
}

// Free weights: x is rational in q, so each iteration minimizes
// (1/2) sum |x(u_k; q) - p_k|^2 + (s/2) ... with NLopt's LD_LBFGS, gradient
// sum L_k^T (x_k - p_k) - s f_int(q), weights bounded below by the model's minimum weight.
struct NonlinearFit {
  const DNurbsModel* model = nullptr;
  const Eigen::MatrixX3d* points = nullptr;
  const Eigen::MatrixX2d* parameters = nullptr;
  double smoothness = 0.0;
  Eigen::VectorXd start;
  std::vector<int> free;

  Eigen::VectorXd coordinates(const double* x) const {
    Eigen::VectorXd q = start;
    for (size_t k = 0; k < free.size(); ++k) {
      q[free[k]] = x[k];
    }
    return q;
  }
};

double nonlinear_objective(unsigned n, const double* x, double* grad, void* data) {
  const auto& fit = *static_cast<const NonlinearFit*>(data);
  const Eigen::VectorXd q = fit.coordinates(x);
  double value = 0.0;
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(q.size());
  for (Eigen::Index k = 0; k < fit.points->rows(); ++k) {
    const Eigen::Vector2d u = fit.parameters->row(k).transpose();
    const Eigen::Vector3d r = fit.model->position(q, u) - fit.points->row(k).transpose();
    value += 0.5 * r.squaredNorm();
    if (grad != nullptr) {
      gradient += fit.model->position_jacobian(q, u).transpose() * r;
    }
  }
  if (fit.smoothness > 0.0) {
    value += fit.smoothness * fit.model->potential_energy(q);
    if (grad != nullptr) {
      Eigen::VectorXd internal = Eigen::VectorXd::Zero(q.size());
      fit.model->add_internal_force(q, internal);
      gradient -= fit.smoothness * internal;
    }
  }
  if (grad != nullptr) {
    for (unsigned k = 0; k < n; ++k) {
      grad[k] = gradient[fit.free[k]];
    }
  }
  return value;
}

Eigen::VectorXd solve_nonlinear_least_squares(const DNurbsModel& model, const Eigen::VectorXd& q0,
                                              const Eigen::MatrixX3d& points,
                                              const Eigen::MatrixX2d& parameters,
                                              double smoothness) {
  NonlinearFit fit;
  fit.model = &model;
  fit.points = &points;
  fit.parameters = &parameters;
  fit.smoothness = smoothness;
  fit.start = q0;
  const int n = model.coordinate_count();
  std::vector<bool> held(static_cast<size_t>(n), false);
  for (const int fixed : model.fixed_coordinates()) {
    held[static_cast<size_t>(fixed)] = true;
  }
  std::vector<bool> is_weight(static_cast<size_t>(n), false);
  for (int c = 0; c < model.control_point_count(); ++c) {
    is_weight[static_cast<size_t>(model.weight_offset(c))] = true;
  }
  std::vector<double> x;
  std::vector<double> lower;
  for (int i = 0; i < n; ++i) {
    if (!held[static_cast<size_t>(i)]) {
      fit.free.push_back(i);
      const double bound = is_weight[static_cast<size_t>(i)] ? model.minimum_weight() : -HUGE_VAL;
      lower.push_back(bound);
      x.push_back(std::max(q0[i], bound));
    }
  }
  nlopt::opt optimizer(nlopt::LD_LBFGS, static_cast<unsigned>(fit.free.size()));
  optimizer.set_lower_bounds(lower);
  optimizer.set_min_objective(nonlinear_objective, &fit);
  optimizer.set_xtol_rel(1e-12);
  optimizer.set_maxeval(2000);
  double value = 0.0;
  try {
    optimizer.optimize(x, value);
  } catch (const nlopt::roundoff_limited&) {
    // The best point so far is in x: round-off stops LBFGS near the optimum.
  } catch (const std::invalid_argument& error) {
    throw make_error("NLopt rejected the free-weight fit (", fit.free.size(),
                     " variables): ", error.what());
  } catch (const std::runtime_error&) {
    // NLopt's generic failure (line search): x holds the best point found.
  }
  Eigen::VectorXd q = fit.coordinates(x.data());
  if (!q.allFinite()) {
    throw make_error("the free-weight fit produced non-finite coordinates");
  }
  return q;
}

double rms(const Eigen::VectorXd& distances) {
  return std::sqrt(distances.squaredNorm() / static_cast<double>(distances.size()));
}

// Shared loop: Shape(q) gives the NURBS, project(shape, p) gives (parameter, distance).
template <typename ShapeAt, typename Project>
DNurbsFitResult fit(const DNurbsModel& model, const Eigen::MatrixX3d& points,
                    const DNurbsFitSettings& settings, ShapeAt shape_at, Project project,
                    double domain_size) {
  check_settings(settings);
  check_points(points, "points to fit");
  DNurbsFitResult result;
  result.coordinates = model.initial_coordinates();
  result.parameters = Eigen::MatrixX2d::Zero(points.rows(), 2);
  Eigen::VectorXd distances(points.rows());

  // Start: project onto the initial shape.
  {
    const auto shape = shape_at(result.coordinates);
    for (Eigen::Index k = 0; k < points.rows(); ++k) {
      result.parameters.row(k) = project(shape, points.row(k).transpose(), distances[k]);
    }
  }
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    result.coordinates =
        model.weight_mode() == WeightMode::kFixed
            ? solve_least_squares(model, result.coordinates, points, result.parameters,
                                  settings.smoothness)
            : solve_nonlinear_least_squares(model, result.coordinates, points, result.parameters,
                                            settings.smoothness);
    ++result.iterations;
    // Parameter correction: re-project onto the new shape.
    const auto shape = shape_at(result.coordinates);
    double moved = 0.0;
    for (Eigen::Index k = 0; k < points.rows(); ++k) {
      const Eigen::Vector2d u = project(shape, points.row(k).transpose(), distances[k]);
      moved = std::max(moved, (u - result.parameters.row(k).transpose()).lpNorm<Eigen::Infinity>());
      result.parameters.row(k) = u.transpose();
    }
    if (settings.on_iteration) {
      settings.on_iteration(result.iterations, rms(distances));
    }
    if (moved <= settings.parameter_tolerance * domain_size) {
      break;
    }
  }
  result.rms_error = rms(distances);
  result.max_error = distances.maxCoeff();
  return result;
}

}  // namespace

DNurbsFitResult fit_dnurbs_surface(const DNurbsSurface& model, const Eigen::MatrixX3d& points,
                                   const DNurbsFitSettings& settings) {
  const NurbsSurface& initial = model.initial_surface();
  const double domain = std::max(initial.knots_u().domain_end() - initial.knots_u().domain_start(),
                                 initial.knots_v().domain_end() - initial.knots_v().domain_start());
  return fit(
      model, points, settings, [&model](const Eigen::VectorXd& q) { return model.surface(q); },
      [](const NurbsSurface& surface, const Eigen::Vector3d& point, double& distance) {
        const SurfaceProjection projection = closest_point(surface, point);
        distance = projection.distance;
        return Eigen::Vector2d(projection.parameter);
      },
      domain);
}

DNurbsFitResult fit_dnurbs_curve(const DNurbsCurve& model, const Eigen::MatrixX3d& points,
                                 const DNurbsFitSettings& settings) {
  const NurbsCurve& initial = model.initial_curve();
  const double domain = initial.knots().domain_end() - initial.knots().domain_start();
  return fit(
      model, points, settings, [&model](const Eigen::VectorXd& q) { return model.curve(q); },
      [](const NurbsCurve& curve, const Eigen::Vector3d& point, double& distance) {
        const CurveProjection projection = closest_point(curve, point);
        distance = projection.distance;
        return Eigen::Vector2d(projection.parameter, 0.0);
      },
      domain);
}

}  // namespace dnurbs
