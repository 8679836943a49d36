#include "design/superquadric_fitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <nlopt.hpp>

#include "design/point_set.h"
#include "nurbs/error.h"

namespace dnurbs {
namespace {

// Optimisation variables: centre (3), rotation vector (3), sizes (3), e1, e2, t1, t2, b1.
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

// Radial distance of body-frame point p (undo bend, then taper; z unchanged by both).
double body_radial_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& size, double e1,
                            double e2, double t1, double t2, double b1, double b2, double b3) {
  const double h = size.z();
  const double z = p.z();
  const double bent_x = p.x() - b1 * std::cos((z + b2) / h * std::numbers::pi * b3);
  const double f1 = t1 * z / h + 1.0;
  const double f2 = t2 * z / h + 1.0;
  // Where a taper factor vanishes the inverse does not exist: a large residual.
  const double big = 10.0 * size.maxCoeff();
  if (f1 <= 1e-9 || f2 <= 1e-9) {
    return big;
  }
  const Eigen::Vector3d e(bent_x / f1, p.y() / f2, z);
  const double gx = std::pow(std::abs(e.x()) / size.x(), 2.0 / e2);
  const double gy = std::pow(std::abs(e.y()) / size.y(), 2.0 / e2);
  const double gz = std::pow(std::abs(e.z()) / size.z(), 2.0 / e1);
  const double F = std::pow(gx + gy, e2 / e1) + gz;
  const double radius = e.norm();
  if (!(F > 0.0) || !std::isfinite(F)) {
    return F > 0.0 ? big : -size.minCoeff();
  }
  const double d = radius * (1.0 - std::pow(F, -0.5 * e1));
  return std::isfinite(d) ? d : big;
}

struct Problem {
  const Eigen::MatrixX3d* points = nullptr;
  const SuperquadricFitSettings* settings = nullptr;
  int evaluations = 0;
};

double objective(unsigned, const double* x, double*, void* data) {
  auto& problem = *static_cast<Problem*>(data);
  ++problem.evaluations;
  // Same rotation for every point: evaluate it once.
  const Eigen::Vector3d c(x[kCentre], x[kCentre + 1], x[kCentre + 2]);
  const Eigen::Matrix3d R =
      rotation_from_vector(Eigen::Vector3d(x[kRotation], x[kRotation + 1], x[kRotation + 2]));
  const Eigen::Vector3d size(x[kSize], x[kSize + 1], x[kSize + 2]);
  double sum = 0.0;
  for (Eigen::Index k = 0; k < problem.points->rows(); ++k) {
    const Eigen::Vector3d p = R.transpose() * (problem.points->row(k).transpose() - c);
    const double d =
        body_radial_distance(p, size, x[kE1], x[kE2], x[kT1], x[kT2], x[kB1],
                             problem.settings->bend_offset, problem.settings->bend_frequency);
    sum += d * d;
  }
  return sum / static_cast<double>(problem.points->rows());
}

// One BOBYQA run from x (updated in place); returns the objective.
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
  std::vector<double> step(kVariableCount, 0.05 * scale);
  for (int i = kRotation; i < kRotation + 3; ++i) {
    step[static_cast<size_t>(i)] = 0.1;
  }
  for (const int i : {kE1, kE2, kT1, kT2}) {
    step[static_cast<size_t>(i)] = 0.05;
  }
  nlopt::opt optimizer(nlopt::LN_BOBYQA, kVariableCount);
  optimizer.set_lower_bounds(lower);
  optimizer.set_upper_bounds(upper);
  optimizer.set_initial_step(step);
  optimizer.set_min_objective(objective, &problem);
  optimizer.set_xtol_rel(tolerance);
  optimizer.set_maxeval(max_evaluations);
  double value = 0.0;
  try {
    status = static_cast<int>(optimizer.optimize(x, value));
  } catch (const nlopt::roundoff_limited&) {
    status = static_cast<int>(nlopt::ROUNDOFF_LIMITED);
    value = objective(kVariableCount, x.data(), nullptr, &problem);
  } catch (const std::runtime_error&) {
    status = static_cast<int>(nlopt::FAILURE);
    value = objective(kVariableCount, x.data(), nullptr, &problem);
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

SuperquadricFitResult fit_superquadric(const Eigen::MatrixX3d& points,
                                       const SuperquadricFitSettings& settings) {
  check_points(points, "points to fit");
  if (points.rows() < kVariableCount - 2) {
    throw make_error("a superquadric fit needs at least ", kVariableCount - 2, " points (got ",
                     points.rows(), ")");
  }
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

  // Start: centroid and principal axes of the points.
  const Eigen::RowVector3d centroid = points.colwise().mean();
  const Eigen::MatrixX3d centred = points.rowwise() - centroid;
  const Eigen::Matrix3d covariance =
      centred.transpose() * centred / static_cast<double>(points.rows());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Matrix3d axes = eigen.eigenvectors();
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
