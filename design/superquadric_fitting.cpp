#include "dnurbs/design/superquadric_fitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>
#include <nlopt.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/design/superquadric_radial_distance.h"

namespace dnurbs {
namespace {

// Optimization variables: centre (3), rotation vector (3), sizes (3), e1, e2, then the global
// deformation (t1, t2, b1, b2, b3, tau, sx, sy) in the order of GlobalDeformationParameters.
constexpr int kVariableCount = kSuperquadricFitVariableCount;
enum : int { kCentre = 0, kRotation = 3, kSize = 6, kE1 = 9, kE2 = 10 };
constexpr int kDeformation = 11;
using G = GlobalDeformationParameter;
constexpr int kT1 = kDeformation + G::kTaper1;
constexpr int kT2 = kDeformation + G::kTaper2;
constexpr int kB1 = kDeformation + G::kBendAmplitude;
constexpr int kB2 = kDeformation + G::kBendOffset;
constexpr int kB3 = kDeformation + G::kBendFrequency;
constexpr int kTau = kDeformation + G::kTwist;
constexpr int kSx = kDeformation + G::kShearX;
constexpr int kSy = kDeformation + G::kShearY;
static_assert(kSy == kVariableCount - 1);

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

// The radial distances d_k at the 19 variables x and, if `jacobian` is not null, their
// derivatives dd_k/dx (#points by 19).
void radial_distances(const Eigen::MatrixX3d& points, const double* x, Eigen::VectorXd& distances,
                      Eigen::MatrixXd* jacobian) {
  const Eigen::Vector3d c(x[kCentre], x[kCentre + 1], x[kCentre + 2]);
  const Eigen::Vector3d r(x[kRotation], x[kRotation + 1], x[kRotation + 2]);
  // Same rotation for every point: evaluate it once.
  const Eigen::Matrix3d R = rotation_from_vector(r);
  const Eigen::Vector3d size(x[kSize], x[kSize + 1], x[kSize + 2]);
  const Eigen::Map<const GlobalDeformationParameters> deformation(x + kDeformation);
  // p = R^T (x - c) = exp(-[r]x) (x - c): dp/dc = -R^T and dp/dr = R^T [x - c]x J_l(r).
  const Eigen::Matrix3d rotation_jacobian =
      jacobian != nullptr ? left_jacobian(r) : Eigen::Matrix3d();
  distances.resize(points.rows());
  if (jacobian != nullptr) {
    jacobian->resize(points.rows(), kVariableCount);
  }
  SuperquadricRadialDistanceGradient local;
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Eigen::Vector3d v = points.row(k).transpose() - c;
    const Eigen::Vector3d p = R.transpose() * v;
    distances[k] = superquadric_body_radial_distance(size, x[kE1], x[kE2], deformation, p,
                                                     jacobian != nullptr ? &local : nullptr);
    if (jacobian != nullptr) {
      const Eigen::Vector3d world = R * local.point;
      auto row = jacobian->row(k);
      row.segment<3>(kCentre) = -world.transpose();
      row.segment<3>(kRotation) = (rotation_jacobian.transpose() * world.cross(v)).transpose();
      row.segment<3>(kSize) = local.size.transpose();
      row[kE1] = local.e1;
      row[kE2] = local.e2;
      row.segment<kGlobalDeformationParameterCount>(kDeformation) = local.deformation.transpose();
    }
  }
}

// (1/N) sum_k d_k^2 at the 19 variables x and its gradient (2/N) sum_k d_k dd_k/dx over all of
// them (if `gradient` is not null).
double mean_squared_distance(const Eigen::MatrixX3d& points, const double* x, double* gradient) {
  Eigen::VectorXd distances;
  Eigen::MatrixXd jacobian;
  radial_distances(points, x, distances, gradient != nullptr ? &jacobian : nullptr);
  const auto n = static_cast<double>(points.rows());
  if (gradient != nullptr) {
    Eigen::Map<Eigen::Matrix<double, kVariableCount, 1>> total(gradient);
    total = (2.0 / n) * (jacobian.transpose() * distances);
  }
  return distances.squaredNorm() / n;
}

void check_settings(const SuperquadricFitSettings& settings) {
  if (settings.max_evaluations <= 0 || settings.start_evaluations <= 0 ||
      !(settings.minimum_exponent > 0.0) ||
      !(settings.maximum_exponent > settings.minimum_exponent) ||
      !(settings.maximum_taper > 0.0 && settings.maximum_taper < 1.0) ||
      !(settings.maximum_twist > 0.0) || !std::isfinite(settings.maximum_twist) ||
      !(settings.maximum_shear > 0.0) || !std::isfinite(settings.maximum_shear) ||
      !std::isfinite(settings.bend_offset) || !std::isfinite(settings.bend_frequency) ||
      !(settings.variable_tolerance >= 0.0)) {
    throw make_error("bad superquadric fit settings (max_evaluations ", settings.max_evaluations,
                     ", start_evaluations ", settings.start_evaluations, ", exponents [",
                     settings.minimum_exponent, ", ", settings.maximum_exponent,
                     "], maximum_taper ", settings.maximum_taper, ", maximum_twist ",
                     settings.maximum_twist, ", maximum_shear ", settings.maximum_shear,
                     ", bend b2 ", settings.bend_offset, " b3 ", settings.bend_frequency,
                     ", variable_tolerance ", settings.variable_tolerance, ")");
  }
  if (settings.local) {
    validate_superquadric_local_fit_settings(*settings.local);
  }
}

// The fitted variables (indices into the 19) under these settings.
std::vector<int> free_variables(const SuperquadricFitSettings& settings) {
  std::vector<int> free;
  for (int i = 0; i < kVariableCount; ++i) {
    const bool bend_shape = i == kB2 || i == kB3;
    const bool shear = i == kSx || i == kSy;
    if ((bend_shape && !settings.fit_bend_shape) || (i == kTau && !settings.fit_twist) ||
        (shear && !settings.fit_shear)) {
      continue;
    }
    free.push_back(i);
  }
  return free;
}

struct Problem {
  const Eigen::MatrixX3d* points = nullptr;
  const SuperquadricFitSettings* settings = nullptr;
  std::vector<int> free;     // fitted variables
  std::vector<double> full;  // all 19, the held ones at their values
  int evaluations = 0;
  double best = std::numeric_limits<double>::infinity();  // lowest objective so far
};

// Counts one evaluation of the objective (with `value`) for the result and the progress report.
void count_evaluation(Problem& problem, double value) {
  ++problem.evaluations;
  problem.best = std::min(problem.best, value);
  if (problem.settings->on_evaluation) {
    problem.settings->on_evaluation(problem.evaluations, std::sqrt(problem.best));
  }
}

double objective(unsigned, const double* x, double* gradient, void* data) {
  auto& problem = *static_cast<Problem*>(data);
  for (size_t i = 0; i < problem.free.size(); ++i) {
    problem.full[static_cast<size_t>(problem.free[i])] = x[i];
  }
  std::array<double, kVariableCount> full_gradient{};
  const double value = mean_squared_distance(*problem.points, problem.full.data(),
                                             gradient != nullptr ? full_gradient.data() : nullptr);
  if (gradient != nullptr) {
    for (size_t i = 0; i < problem.free.size(); ++i) {
      gradient[i] = full_gradient[static_cast<size_t>(problem.free[i])];
    }
  }
  count_evaluation(problem, value);
  return value;
}

// Bounds of the 19 variables.
void variable_bounds(const SuperquadricFitSettings& s, double scale, std::vector<double>& lower,
                     std::vector<double>& upper) {
  const double inf = std::numeric_limits<double>::infinity();
  lower.assign(kVariableCount, -inf);
  upper.assign(kVariableCount, inf);
  const auto bound = [&](int i, double low, double high) {
    lower[static_cast<size_t>(i)] = low;
    upper[static_cast<size_t>(i)] = high;
  };
  for (int i = 0; i < 3; ++i) {
    bound(kSize + i, 1e-3 * scale, 10.0 * scale);
  }
  bound(kE1, s.minimum_exponent, s.maximum_exponent);
  bound(kE2, s.minimum_exponent, s.maximum_exponent);
  bound(kT1, -s.maximum_taper, s.maximum_taper);
  bound(kT2, -s.maximum_taper, s.maximum_taper);
  bound(kB2, -10.0 * scale, 10.0 * scale);
  bound(kB3, 1e-3, 4.0);
  bound(kTau, -s.maximum_twist, s.maximum_twist);
  bound(kSx, -s.maximum_shear, s.maximum_shear);
  bound(kSy, -s.maximum_shear, s.maximum_shear);
}

// One bounded run from x (all 19, the fitted ones updated in place); returns the objective.
double run(Problem& problem, std::vector<double>& x, double scale, int max_evaluations,
           double tolerance, int& status) {
  const SuperquadricFitSettings& s = *problem.settings;
  std::vector<double> lower;
  std::vector<double> upper;
  variable_bounds(s, scale, lower, upper);
  const size_t n = problem.free.size();
  std::vector<double> y(n);
  std::vector<double> free_lower(n);
  std::vector<double> free_upper(n);
  for (size_t i = 0; i < n; ++i) {
    const auto j = static_cast<size_t>(problem.free[i]);
    free_lower[i] = lower[j];
    free_upper[i] = upper[j];
    y[i] = std::clamp(x[j], lower[j], upper[j]);
  }
  problem.full = x;
  const bool derivative_free = s.algorithm == SuperquadricFitAlgorithm::kBobyqa;
  nlopt::opt optimizer(derivative_free ? nlopt::LN_BOBYQA : nlopt::LD_LBFGS,
                       static_cast<unsigned>(n));
  optimizer.set_lower_bounds(free_lower);
  optimizer.set_upper_bounds(free_upper);
  if (derivative_free) {
    std::vector<double> step(n, 0.05 * scale);
    for (size_t i = 0; i < n; ++i) {
      const int j = problem.free[i];
      if (j >= kRotation && j < kRotation + 3) {
        step[i] = 0.1;
      } else if (j >= kE1 && j != kB1 && j != kB2) {
        step[i] = 0.05;  // dimensionless: exponents, tapers, b3, twist, shears
      }
    }
    optimizer.set_initial_step(step);
  }
  optimizer.set_min_objective(objective, &problem);
  optimizer.set_xtol_rel(tolerance);
  optimizer.set_maxeval(max_evaluations);
  double value = 0.0;
  try {
    status = static_cast<int>(optimizer.optimize(y, value));
  } catch (const nlopt::roundoff_limited&) {
    status = static_cast<int>(nlopt::ROUNDOFF_LIMITED);
    value = std::numeric_limits<double>::quiet_NaN();
  } catch (const std::runtime_error&) {
    status = static_cast<int>(nlopt::FAILURE);
    value = std::numeric_limits<double>::quiet_NaN();
  }
  for (size_t i = 0; i < n; ++i) {
    x[static_cast<size_t>(problem.free[i])] = y[i];
  }
  if (std::isnan(value)) {
    value = mean_squared_distance(*problem.points, x.data(), nullptr);
  }
  return value;
}

// Levenberg-Marquardt on the residuals d_k from x (all 19, the fitted ones within their bounds
// and updated in place): the least-squares structure LBFGS ignores converges quadratically near
// a zero residual and to the exact minimizer otherwise. Steps are clamped to the bounds; the
// polish ends when no damping lowers sum d_k^2 (or after max_iterations steps).
void levenberg_marquardt_polish(Problem& problem, std::vector<double>& x, double scale,
                                int max_iterations) {
  const Eigen::MatrixX3d& points = *problem.points;
  const auto count = static_cast<double>(points.rows());
  std::vector<double> lower;
  std::vector<double> upper;
  variable_bounds(*problem.settings, scale, lower, upper);
  const auto n = static_cast<Eigen::Index>(problem.free.size());
  Eigen::VectorXd distances;
  Eigen::MatrixXd jacobian;
  radial_distances(points, x.data(), distances, &jacobian);
  double cost = distances.squaredNorm();
  count_evaluation(problem, cost / count);
  double damping = 1e-3;
  std::vector<double> trial = x;
  Eigen::VectorXd trial_distances;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::MatrixXd free_jacobian(points.rows(), n);
    for (Eigen::Index i = 0; i < n; ++i) {
      free_jacobian.col(i) = jacobian.col(problem.free[static_cast<size_t>(i)]);
    }
    const Eigen::MatrixXd normal = free_jacobian.transpose() * free_jacobian;
    const Eigen::VectorXd gradient = free_jacobian.transpose() * distances;
    const double floor = 1e-15 * normal.diagonal().maxCoeff();
    bool improved = false;
    while (!improved && damping < 1e12) {
      Eigen::MatrixXd damped = normal;
      damped.diagonal().array() += damping * (normal.diagonal().array() + floor);
      const Eigen::VectorXd step = damped.ldlt().solve(-gradient);
      for (Eigen::Index i = 0; i < n; ++i) {
        const auto j = static_cast<size_t>(problem.free[static_cast<size_t>(i)]);
        trial[j] = std::clamp(x[j] + step[i], lower[j], upper[j]);
      }
      radial_distances(points, trial.data(), trial_distances, nullptr);
      const double trial_cost = trial_distances.squaredNorm();
      count_evaluation(problem, trial_cost / count);
      if (trial_cost < cost) {
        x = trial;
        cost = trial_cost;
        damping = std::max(damping / 3.0, 1e-12);
        improved = true;
      } else {
        damping *= 4.0;
      }
    }
    if (!improved) {
      return;
    }
    radial_distances(points, x.data(), distances, &jacobian);
  }
}

// The 19 variables of a start.
std::vector<double> start_variables(const SuperquadricFitStart& start) {
  using P = SuperquadricShapeParameter;
  const DeformableSuperquadricShape checked(start.shape);  // validates q_s
  if (!start.centre.allFinite() || !start.rotation.allFinite() ||
      !(start.rotation.transpose() * start.rotation).isIdentity(1e-9) ||
      !(start.rotation.determinant() > 0.0)) {
    throw make_error("superquadric fit start: the centre (", start.centre.transpose(),
                     ") must be finite and the rotation proper orthogonal (det ",
                     start.rotation.determinant(), ")");
  }
  std::vector<double> x(kVariableCount, 0.0);
  const Eigen::Vector3d r = vector_from_rotation(start.rotation);
  for (int i = 0; i < 3; ++i) {
    x[static_cast<size_t>(kCentre + i)] = start.centre[i];
    x[static_cast<size_t>(kRotation + i)] = r[i];
    x[static_cast<size_t>(kSize + i)] = start.shape[P::kScale] * start.shape[P::kAspect1 + i];
  }
  x[kE1] = start.shape[P::kSquareness1];
  x[kE2] = start.shape[P::kSquareness2];
  for (int i = 0; i < kGlobalDeformationParameterCount; ++i) {
    x[static_cast<size_t>(kDeformation + i)] = start.shape[P::kTaper1 + i];
  }
  return x;
}

// The best of the 24 principal-axes starts (every axis assignment and proper sign choice), each
// run with twist, shear, b2 and b3 held: the pose, sizes, squareness, taper and bend first.
std::vector<double> best_principal_start(Problem& problem, const Eigen::MatrixX3d& points,
                                         double scale, int& status) {
  const SuperquadricFitSettings& settings = *problem.settings;
  const std::vector<int> all_free = problem.free;
  std::erase_if(problem.free, [](int i) { return i >= kB2; });
  const Eigen::RowVector3d centroid = points.colwise().mean();
  const Eigen::MatrixX3d centred = points.rowwise() - centroid;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred.transpose() * centred /
                                                             static_cast<double>(points.rows()));
  const Eigen::Matrix3d& axes = eigen.eigenvectors();
  const std::array<std::array<int, 3>, 6> permutations = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_x;
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
      x[kB2] = settings.bend_offset;
      x[kB3] = settings.bend_frequency;
      const double value = run(problem, x, scale, settings.start_evaluations, 1e-6, status);
      if (value < best) {
        best = value;
        best_x = x;
      }
    }
  }
  problem.free = all_free;
  return best_x;
}

}  // namespace

double superquadric_fit_objective(const Eigen::MatrixX3d& points,
                                  const SuperquadricFitSettings& settings,
                                  const Eigen::VectorXd& variables, Eigen::VectorXd* gradient) {
  check_points(points, "points to fit");
  check_settings(settings);
  if (variables.size() != kVariableCount) {
    throw make_error("a superquadric fit has ", kVariableCount, " variables (got ",
                     variables.size(), ")");
  }
  if (gradient == nullptr) {
    return mean_squared_distance(points, variables.data(), nullptr);
  }
  gradient->resize(kVariableCount);
  return mean_squared_distance(points, variables.data(), gradient->data());
}

SuperquadricFitResult fit_superquadric(const Eigen::MatrixX3d& points,
                                       const SuperquadricFitSettings& settings) {
  check_points(points, "points to fit");
  check_settings(settings);
  Problem problem;
  problem.points = &points;
  problem.settings = &settings;
  problem.free = free_variables(settings);
  if (points.rows() < static_cast<Eigen::Index>(problem.free.size())) {
    throw make_error("a superquadric fit of ", problem.free.size(),
                     " parameters needs at least as many points (got ", points.rows(), ")");
  }
  const Eigen::RowVector3d centroid = points.colwise().mean();
  const Eigen::MatrixX3d centred = points.rowwise() - centroid;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred.transpose() * centred /
                                                             static_cast<double>(points.rows()));
  const double scale = std::sqrt(std::max(eigen.eigenvalues().maxCoeff(), 0.0)) * 2.0;
  if (!(eigen.eigenvalues().minCoeff() > 1e-12 * eigen.eigenvalues().maxCoeff()) ||
      !(scale > 0.0)) {
    throw make_error("the points to fit lie on a plane or a line (covariance eigenvalues ",
                     eigen.eigenvalues().transpose().format(Eigen::IOFormat(6, 0, ", ", ", ")),
                     "): no superquadric is determined");
  }

  int status = 0;
  std::vector<double> x = settings.start ? start_variables(*settings.start)
                                         : best_principal_start(problem, points, scale, status);
  // Polish the start; with derivatives, finish with the least-squares steps.
  run(problem, x, scale, settings.max_evaluations, settings.variable_tolerance, status);
  if (settings.algorithm == SuperquadricFitAlgorithm::kLbfgs) {
    levenberg_marquardt_polish(problem, x, scale, 100);
  }

  // Canonical representative (header): b1 >= 0 (rotate by pi about z), then t1 >= 0 (about x).
  Eigen::Matrix3d R =
      rotation_from_vector(Eigen::Vector3d(x[kRotation], x[kRotation + 1], x[kRotation + 2]));
  if (x[kB1] < 0.0) {
    x[kB1] = -x[kB1];
    x[kSx] = -x[kSx];
    x[kSy] = -x[kSy];
    R.col(0) = -R.col(0);
    R.col(1) = -R.col(1);
  }
  if (x[kT1] < 0.0 || (x[kT1] == 0.0 && x[kT2] < 0.0)) {
    x[kT1] = -x[kT1];
    x[kT2] = -x[kT2];
    x[kB2] = -x[kB2];
    x[kSx] = -x[kSx];
    R.col(1) = -R.col(1);
    R.col(2) = -R.col(2);
  }
  using P = SuperquadricShapeParameter;
  SuperquadricFitResult result;
  result.shape.setZero();
  result.shape[P::kScale] = 1.0;
  for (int i = 0; i < 3; ++i) {
    result.shape[P::kAspect1 + i] = x[static_cast<size_t>(kSize + i)];
    result.centre[i] = x[static_cast<size_t>(kCentre + i)];
  }
  result.shape[P::kSquareness1] = x[kE1];
  result.shape[P::kSquareness2] = x[kE2];
  for (int i = 0; i < kGlobalDeformationParameterCount; ++i) {
    result.shape[P::kTaper1 + i] = x[static_cast<size_t>(kDeformation + i)];
  }
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
  if (settings.local) {
    result.local = fit_superquadric_local_displacements(points, result.shape, result.centre,
                                                        result.rotation, *settings.local);
  }
  return result;
}

}  // namespace dnurbs
