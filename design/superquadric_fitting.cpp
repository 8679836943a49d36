#include "dnurbs/design/superquadric_fitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <nlopt.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/design/point_set.h"

namespace dnurbs {
namespace {

// Optimization variables: centre (3), rotation vector (3), sizes (3), e1, e2, t1, t2, b1.
constexpr int kVariableCount = 14;
enum : int {
  kCentre = 0,
  kRotation = 3,
  kSize = 6,
  kE1 = 9,
  kE2 = 10,
  kT1 = 11,
  kT2 = 12,
  kB1 = 13
};

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle == 0.0) {
    return Eigen::Matrix3d::Identity();
  }
  return Eigen::AngleAxisd(angle, r / angle).toRotationMatrix();
}

Eigen::Vector3d vector_from_rotation(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd angle_axis(rotation);
  return angle_axis.angle() * angle_axis.axis();
}

// Partial derivatives of the body-frame radial distance: with respect to the body point p, the
// sizes (A1, A2, A3) and the exponents e1, e2, tapers t1, t2 and bend amplitude b1.
struct BodyDistanceGradient {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  double e1 = 0.0;
  double e2 = 0.0;
  double t1 = 0.0;
  double t2 = 0.0;
  double b1 = 0.0;
};

// g^n = (|e| / A)^n of the inside-outside function with its partial derivatives
// d/de = n g / e, d/dA = -n g / A and d/dn = g ln(|e| / A) (all 0 where e = 0 and g = 0).
struct PowerTerm {
  double value = 0.0;
  double d_coordinate = 0.0;
  double d_size = 0.0;
  double d_power = 0.0;
};

PowerTerm power_term(double coordinate, double size, double power) {
  PowerTerm term;
  if (coordinate == 0.0) {
    return term;
  }
  const double ratio = std::abs(coordinate) / size;
  term.value = std::pow(ratio, power);
  term.d_coordinate = power * term.value / coordinate;
  term.d_size = -power * term.value / size;
  term.d_power = term.value * std::log(ratio);
  return term;
}

// Radial distance of body-frame point p (undo bend, then taper; z unchanged by both) and, if
// `gradient` is not null, its partial derivatives by reverse-mode differentiation of the steps
// below (zero on the guarded branches, where the distance is a constant).
double body_radial_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& size, double e1,
                            double e2, double t1, double t2, double b1, double b2, double b3,
                            BodyDistanceGradient* gradient = nullptr) {
  if (gradient != nullptr) {
    *gradient = BodyDistanceGradient{};
  }
  const double h = size.z();
  const double z = p.z();
  const double bend_rate = std::numbers::pi * b3 / h;
  const double bend_angle = (z + b2) * bend_rate;
  const double bent_x = p.x() - b1 * std::cos(bend_angle);
  const double f1 = t1 * z / h + 1.0;
  const double f2 = t2 * z / h + 1.0;
  // Where a taper factor vanishes the inverse does not exist: a large residual.
  const double big = 10.0 * size.maxCoeff();
  if (f1 <= 1e-9 || f2 <= 1e-9) {
    return big;
  }
  const Eigen::Vector3d e(bent_x / f1, p.y() / f2, z);
  const PowerTerm gx = power_term(e.x(), size.x(), 2.0 / e2);
  const PowerTerm gy = power_term(e.y(), size.y(), 2.0 / e2);
  const PowerTerm gz = power_term(e.z(), size.z(), 2.0 / e1);
  const double sum_xy = gx.value + gy.value;
  const double lateral = std::pow(sum_xy, e2 / e1);
  const double F = lateral + gz.value;
  const double radius = e.norm();
  if (!(F > 0.0) || !std::isfinite(F)) {
    return F > 0.0 ? big : -size.minCoeff();
  }
  const double G = std::pow(F, -0.5 * e1);
  const double d = radius * (1.0 - G);
  if (!std::isfinite(d)) {
    return big;
  }
  if (gradient == nullptr) {
    return d;
  }
  // d = |e| (1 - G), G = F^(-e1/2), F = S^(e2/e1) + gz, S = gx + gy (the inside-outside
  // function of the superellipsoid e of Terzopoulos 2003, eq. 1.30, see the header); adjoints
  // accumulate backwards.
  BodyDistanceGradient& g = *gradient;
  const double adjoint_radius = 1.0 - G;
  const double adjoint_G = -radius;
  const double adjoint_F = adjoint_G * (-0.5 * e1) * G / F;
  g.e1 += adjoint_G * (-0.5 * std::log(F)) * G;
  double adjoint_S = 0.0;
  if (sum_xy > 0.0) {
    adjoint_S = adjoint_F * (e2 / e1) * lateral / sum_xy;
    const double log_S = std::log(sum_xy);
    g.e1 += adjoint_F * lateral * log_S * (-e2 / (e1 * e1));
    g.e2 += adjoint_F * lateral * log_S / e1;
  }
  const double adjoint_gz = adjoint_F;
  // g(e, A, n) with n = 2/e2 or 2/e1: dn/de2 = -2/e2^2.
  const double adjoint_ex = adjoint_S * gx.d_coordinate + adjoint_radius * e.x() / radius;
  const double adjoint_ey = adjoint_S * gy.d_coordinate + adjoint_radius * e.y() / radius;
  const double adjoint_ez = adjoint_gz * gz.d_coordinate + adjoint_radius * e.z() / radius;
  g.size.x() += adjoint_S * gx.d_size;
  g.size.y() += adjoint_S * gy.d_size;
  g.size.z() += adjoint_gz * gz.d_size;
  g.e2 += adjoint_S * (gx.d_power + gy.d_power) * (-2.0 / (e2 * e2));
  g.e1 += adjoint_gz * gz.d_power * (-2.0 / (e1 * e1));
  // e = (bent_x / f1, p_y / f2, z).
  const double adjoint_bent_x = adjoint_ex / f1;
  const double adjoint_f1 = -adjoint_ex * e.x() / f1;
  const double adjoint_f2 = -adjoint_ey * e.y() / f2;
  // f_i = t_i z / h + 1, bent_x = p_x - b1 cos((z + b2) pi b3 / h).
  const double bend_slope = adjoint_bent_x * b1 * std::sin(bend_angle);
  g.point.x() = adjoint_bent_x;
  g.point.y() = adjoint_ey / f2;
  g.point.z() = adjoint_ez + (adjoint_f1 * t1 + adjoint_f2 * t2) / h + bend_slope * bend_rate;
  g.size.z() += -(adjoint_f1 * t1 + adjoint_f2 * t2) * z / (h * h) - bend_slope * bend_angle / h;
  g.t1 = adjoint_f1 * z / h;
  g.t2 = adjoint_f2 * z / h;
  g.b1 = -adjoint_bent_x * std::cos(bend_angle);
  return d;
}

// J_l(r) = I + (1 - cos t)/t^2 [r]x + (t - sin t)/t^3 [r]x^2 (t = |r|), the left Jacobian of the
// rotation vector: d(exp([r]x) v) = -[exp([r]x) v]x J_l(r) dr. Series below t = 1e-4.
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& r) {
  const double t = r.norm();
  Eigen::Matrix3d cross;
  cross << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  const double a = t < 1e-4 ? 0.5 - t * t / 24.0 : (1.0 - std::cos(t)) / (t * t);
  const double b = t < 1e-4 ? 1.0 / 6.0 - t * t / 120.0 : (t - std::sin(t)) / (t * t * t);
  return Eigen::Matrix3d::Identity() + a * cross + b * cross * cross;
}

struct Problem {
  const Eigen::MatrixX3d* points = nullptr;
  const SuperquadricFitSettings* settings = nullptr;
  int evaluations = 0;
  double best = std::numeric_limits<double>::infinity();  // lowest objective so far
};

// (1/N) sum_k d_k^2 and its gradient (if `gradient` is not null) over the variables.
double mean_squared_distance(const Problem& problem, const double* x, double* gradient) {
  const Eigen::Vector3d c(x[kCentre], x[kCentre + 1], x[kCentre + 2]);
  const Eigen::Vector3d r(x[kRotation], x[kRotation + 1], x[kRotation + 2]);
  // Same rotation for every point: evaluate it once.
  const Eigen::Matrix3d R = rotation_from_vector(r);
  const Eigen::Vector3d size(x[kSize], x[kSize + 1], x[kSize + 2]);
  const SuperquadricFitSettings& s = *problem.settings;
  Eigen::Map<Eigen::Matrix<double, kVariableCount, 1>> total(gradient);
  if (gradient != nullptr) {
    total.setZero();
  }
  // p = R^T (x - c) = exp(-[r]x) (x - c): dp/dc = -R^T and dp/dr = R^T [x - c]x J_l(r).
  const Eigen::Matrix3d rotation_jacobian =
      gradient != nullptr ? left_jacobian(r) : Eigen::Matrix3d();
  const double n = static_cast<double>(problem.points->rows());
  double sum = 0.0;
  BodyDistanceGradient local;
  for (Eigen::Index k = 0; k < problem.points->rows(); ++k) {
    const Eigen::Vector3d v = problem.points->row(k).transpose() - c;
    const Eigen::Vector3d p = R.transpose() * v;
    const double d =
        body_radial_distance(p, size, x[kE1], x[kE2], x[kT1], x[kT2], x[kB1], s.bend_offset,
                             s.bend_frequency, gradient != nullptr ? &local : nullptr);
    sum += d * d;
    if (gradient != nullptr) {
      const double weight = 2.0 * d / n;
      const Eigen::Vector3d world = R * local.point;
      total.segment<3>(kCentre) -= weight * world;
      total.segment<3>(kRotation) += weight * rotation_jacobian.transpose() * world.cross(v);
      total.segment<3>(kSize) += weight * local.size;
      total[kE1] += weight * local.e1;
      total[kE2] += weight * local.e2;
      total[kT1] += weight * local.t1;
      total[kT2] += weight * local.t2;
      total[kB1] += weight * local.b1;
    }
  }
  return sum / n;
}

void check_settings(const SuperquadricFitSettings& settings) {
  if (settings.max_evaluations <= 0 || settings.start_evaluations <= 0 ||
      !(settings.minimum_exponent > 0.0) ||
      !(settings.maximum_exponent > settings.minimum_exponent) ||
      !(settings.maximum_taper > 0.0 && settings.maximum_taper < 1.0) ||
      !std::isfinite(settings.bend_offset) || !std::isfinite(settings.bend_frequency) ||
      !(settings.variable_tolerance >= 0.0)) {
    throw make_error("bad superquadric fit settings (max_evaluations ", settings.max_evaluations,
                     ", exponents [", settings.minimum_exponent, ", ", settings.maximum_exponent,
                     "], maximum_taper ", settings.maximum_taper, ", bend b2 ",
                     settings.bend_offset, " b3 ", settings.bend_frequency, ")");
  }
}

double objective(unsigned, const double* x, double* gradient, void* data) {
  auto& problem = *static_cast<Problem*>(data);
  ++problem.evaluations;
  const double value = mean_squared_distance(problem, x, gradient);
  problem.best = std::min(problem.best, value);
  if (problem.settings->on_evaluation) {
    problem.settings->on_evaluation(problem.evaluations, std::sqrt(problem.best));
  }
  return value;
}

// One bounded run from x (updated in place); returns the objective.
double run(Problem& problem, std::vector<double>& x, double scale, int max_evaluations,
           double tolerance, int& status) {
  const SuperquadricFitSettings& s = *problem.settings;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> lower(kVariableCount, -inf);
  std::vector<double> upper(kVariableCount, inf);
  for (int i = 0; i < 3; ++i) {
    lower[static_cast<size_t>(kSize + i)] = 1e-3 * scale;
    upper[static_cast<size_t>(kSize + i)] = 10.0 * scale;
  }
  for (const int i : {kE1, kE2}) {
    lower[static_cast<size_t>(i)] = s.minimum_exponent;
    upper[static_cast<size_t>(i)] = s.maximum_exponent;
  }
  for (const int i : {kT1, kT2}) {
    lower[static_cast<size_t>(i)] = -s.maximum_taper;
    upper[static_cast<size_t>(i)] = s.maximum_taper;
  }
  for (int i = 0; i < kVariableCount; ++i) {
    auto& value = x[static_cast<size_t>(i)];
    value = std::clamp(value, lower[static_cast<size_t>(i)], upper[static_cast<size_t>(i)]);
  }
  const bool derivative_free = s.algorithm == SuperquadricFitAlgorithm::kBobyqa;
  nlopt::opt optimizer(derivative_free ? nlopt::LN_BOBYQA : nlopt::LD_LBFGS, kVariableCount);
  optimizer.set_lower_bounds(lower);
  optimizer.set_upper_bounds(upper);
  if (derivative_free) {
    std::vector<double> step(kVariableCount, 0.05 * scale);
    for (int i = kRotation; i < kRotation + 3; ++i) {
      step[static_cast<size_t>(i)] = 0.1;
    }
    for (const int i : {kE1, kE2, kT1, kT2}) {
      step[static_cast<size_t>(i)] = 0.05;
    }
    optimizer.set_initial_step(step);
  }
  optimizer.set_min_objective(objective, &problem);
  optimizer.set_xtol_rel(tolerance);
  optimizer.set_maxeval(max_evaluations);
  double value = 0.0;
  try {
    status = static_cast<int>(optimizer.optimize(x, value));
  } catch (const nlopt::roundoff_limited&) {
    status = static_cast<int>(nlopt::ROUNDOFF_LIMITED);
    value = mean_squared_distance(problem, x.data(), nullptr);
  } catch (const std::runtime_error&) {
    status = static_cast<int>(nlopt::FAILURE);
    value = mean_squared_distance(problem, x.data(), nullptr);
  }
  return value;
}

}  // namespace

double superquadric_radial_distance(const SuperquadricShapeParameters& shape,
                                    const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& x) {
  using P = SuperquadricShapeParameter;
  if (shape[P::kTwist] != 0.0 || shape[P::kShearX] != 0.0 || shape[P::kShearY] != 0.0) {
    throw make_error("the radial distance needs zero twist and shear (tau ", shape[P::kTwist],
                     ", sx ", shape[P::kShearX], ", sy ", shape[P::kShearY], ")");
  }
  const Eigen::Vector3d size = shape[P::kScale] * shape.segment<3>(P::kAspect1);
  return body_radial_distance(rotation.transpose() * (x - centre), size, shape[P::kSquareness1],
                              shape[P::kSquareness2], shape[P::kTaper1], shape[P::kTaper2],
                              shape[P::kBendAmplitude], shape[P::kBendOffset],
                              shape[P::kBendFrequency]);
}

double superquadric_fit_objective(const Eigen::MatrixX3d& points,
                                  const SuperquadricFitSettings& settings,
                                  const Eigen::VectorXd& variables, Eigen::VectorXd* gradient) {
  check_points(points, "points to fit");
  check_settings(settings);
  if (variables.size() != kVariableCount) {
    throw make_error("a superquadric fit has ", kVariableCount, " variables (got ",
                     variables.size(), ")");
  }
  Problem problem;
  problem.points = &points;
  problem.settings = &settings;
  if (gradient == nullptr) {
    return mean_squared_distance(problem, variables.data(), nullptr);
  }
  gradient->resize(kVariableCount);
  return mean_squared_distance(problem, variables.data(), gradient->data());
}

SuperquadricFitResult fit_superquadric(const Eigen::MatrixX3d& points,
                                       const SuperquadricFitSettings& settings) {
  check_points(points, "points to fit");
  if (points.rows() < kVariableCount - 2) {
    throw make_error("a superquadric fit needs at least ", kVariableCount - 2, " points (got ",
                     points.rows(), ")");
  }
  check_settings(settings);

  // Start: centroid and principal axes of the points.
  const Eigen::RowVector3d centroid = points.colwise().mean();
  const Eigen::MatrixX3d centred = points.rowwise() - centroid;
  const Eigen::Matrix3d covariance =
      centred.transpose() * centred / static_cast<double>(points.rows());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Matrix3d& axes = eigen.eigenvectors();
  const double scale = std::sqrt(std::max(eigen.eigenvalues().maxCoeff(), 0.0)) * 2.0;
  if (!(eigen.eigenvalues().minCoeff() > 1e-12 * eigen.eigenvalues().maxCoeff()) ||
      !(scale > 0.0)) {
    throw make_error("the points to fit lie on a plane or a line (covariance eigenvalues ",
                     eigen.eigenvalues().transpose().format(Eigen::IOFormat(6, 0, ", ", ", ")),
                     "): no superquadric is determined");
  }

  Problem problem;
  problem.points = &points;
  problem.settings = &settings;
  SuperquadricFitResult result;
  // Every assignment of the principal axes to body axes, with every proper sign choice.
  const std::array<std::array<int, 3>, 6> permutations = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_x;
  int status = 0;
  for (const auto& permutation : permutations) {
    for (int signs = 0; signs < 4; ++signs) {
      Eigen::Matrix3d R;
      for (int i = 0; i < 3; ++i) {
        R.col(i) = axes.col(permutation[static_cast<size_t>(i)]);
      }
      if (signs & 1) {
        R.col(0) = -R.col(0);
      }
      if (signs & 2) {
        R.col(1) = -R.col(1);
      }
      if (R.determinant() < 0.0) {
        R.col(2) = -R.col(2);
      }
      std::vector<double> x(kVariableCount, 0.0);
      const Eigen::Vector3d r = vector_from_rotation(R);
      const Eigen::MatrixX3d body = centred * R;
      for (int i = 0; i < 3; ++i) {
        x[static_cast<size_t>(kCentre + i)] = centroid[i];
        x[static_cast<size_t>(kRotation + i)] = r[i];
        x[static_cast<size_t>(kSize + i)] = body.col(i).cwiseAbs().maxCoeff();
      }
      x[kE1] = 1.0;
      x[kE2] = 1.0;
      const double value = run(problem, x, scale, settings.start_evaluations, 1e-6, status);
      if (value < best) {
        best = value;
        best_x = x;
      }
    }
  }
  // Polish the best start.
  best = run(problem, best_x, scale, settings.max_evaluations, settings.variable_tolerance, status);
  std::vector<double>& x = best_x;

  // Canonical representative: b1 >= 0 (rotate by pi about z), then t1 >= 0 (about x).
  Eigen::Matrix3d R =
      rotation_from_vector(Eigen::Vector3d(x[kRotation], x[kRotation + 1], x[kRotation + 2]));
  if (x[kB1] < 0.0) {
    x[kB1] = -x[kB1];
    R.col(0) = -R.col(0);
    R.col(1) = -R.col(1);
  }
  if (x[kT1] < 0.0 || (x[kT1] == 0.0 && x[kT2] < 0.0)) {
    x[kT1] = -x[kT1];
    x[kT2] = -x[kT2];
    R.col(1) = -R.col(1);
    R.col(2) = -R.col(2);
  }
  using P = SuperquadricShapeParameter;
  result.shape.setZero();
  result.shape[P::kScale] = 1.0;
  for (int i = 0; i < 3; ++i) {
    result.shape[P::kAspect1 + i] = x[static_cast<size_t>(kSize + i)];
    result.centre[i] = x[static_cast<size_t>(kCentre + i)];
  }
  result.shape[P::kSquareness1] = x[kE1];
  result.shape[P::kSquareness2] = x[kE2];
  result.shape[P::kTaper1] = x[kT1];
  result.shape[P::kTaper2] = x[kT2];
  result.shape[P::kBendAmplitude] = x[kB1];
  result.shape[P::kBendOffset] = settings.bend_offset;
  result.shape[P::kBendFrequency] = settings.bend_frequency;
  result.rotation = R;
  double sum = 0.0;
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const double d = std::abs(superquadric_radial_distance(
        result.shape, result.centre, result.rotation, points.row(k).transpose()));
    sum += d * d;
    result.max_error = std::max(result.max_error, d);
  }
  result.rms_error = std::sqrt(sum / static_cast<double>(points.rows()));
  result.evaluations = problem.evaluations;
  result.status = status;
  (void)best;
  return result;
}

}  // namespace dnurbs
