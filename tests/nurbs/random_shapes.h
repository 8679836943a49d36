#pragma once
// Random shapes for the property tests of the NURBS layer, drawn from a caller's fixed-seed
// generator: degrees 1..7, open (clamped or not) and periodic knot vectors with repeated interior
// knots, seam knots of every multiplicity split between both ends of the period list, period
// lists perturbed by round-off at the seam, and weights from 0.05 to 20. Also the relative
// deviation between two shapes used to check that an operation keeps the shape.

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/nurbs/nurbs_curve.h"
#include "dnurbs/nurbs/nurbs_surface.h"

namespace dnurbs::testing {

/// How a random knot vector is built.
struct RandomKnotOptions {
  bool periodic = false;
  /// Open vectors: end knots repeated p + 1 times (else 1..p + 1 times at random).
  bool clamped = true;
  /// Periodic vectors: seam multiplicity 1..p; 0 draws it at random.
  int seam_multiplicity = 0;
  /// Periodic vectors: move the repeated seam copies by a few ulps of the seam's magnitude, as a
  /// list computed by t_{i+n} - T carries them.
  bool perturb_seam = false;
  /// Control points beyond the fewest the degree allows (p + 1): a periodic polyline through 2
  /// points retraces itself, which point inversion cannot tell apart.
  int extra_control_points = 0;
};

inline int random_int(std::mt19937& generator, int low, int high) {
  return std::uniform_int_distribution<int>(low, high)(generator);
}

inline double random_real(std::mt19937& generator, double low, double high) {
  return std::uniform_real_distribution<double>(low, high)(generator);
}

/// Distinct interior knots in (start, end), each repeated 1..degree times (2 in 5 repeated).
inline std::vector<double> random_interior_knots(int degree, double start, double end,
                                                 int minimum_count, std::mt19937& generator) {
  std::vector<double> distinct;
  const int count = random_int(generator, 0, 4);
  for (int i = 0; i < count; ++i) {
    distinct.push_back(start + (end - start) * random_real(generator, 0.05, 0.95));
  }
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  std::vector<double> knots;
  for (const double knot : distinct) {
    const int multiplicity = random_int(generator, 0, 4) < 2 ? random_int(generator, 1, degree) : 1;
    knots.insert(knots.end(), static_cast<size_t>(multiplicity), knot);
  }
  // Single knots at evenly spread places until there are enough.
  for (int extra = 1; static_cast<int>(knots.size()) < minimum_count; ++extra) {
    const double knot =
        start + (end - start) * (0.5 + 0.37 * std::sin(3.1 * extra)) / (1.0 + 0.01 * extra);
    knots.insert(std::upper_bound(knots.begin(), knots.end(), knot), knot);
  }
  return knots;
}

/// A period list t_p..t_{p+n}: seam copies at both ends, then interior knots, n >= p + 1.
inline std::vector<double> random_period_knots(int degree, const RandomKnotOptions& options,
                                               std::mt19937& generator) {
  const double start = random_real(generator, -3.0, 3.0);
  const double end = start + random_real(generator, 0.5, 4.0);
  const int seam =
      options.seam_multiplicity > 0 ? options.seam_multiplicity : random_int(generator, 1, degree);
  const int at_start = random_int(generator, 1, seam);
  const int at_end = seam - at_start + 1;  // copies of t_{p+n}, the last one included
  const std::vector<double> interior = random_interior_knots(
      degree, start, end, degree + 1 - seam + options.extra_control_points, generator);
  std::vector<double> period(static_cast<size_t>(at_start), start);
  period.insert(period.end(), interior.begin(), interior.end());
  period.insert(period.end(), static_cast<size_t>(at_end), end);
  if (options.perturb_seam) {
    // A few ulps of the seam's magnitude on every copy but the first and the last.
    const double ulp = std::numeric_limits<double>::epsilon() * std::max(std::abs(start), end);
    for (int i = 1; i < at_start; ++i) {
      period[static_cast<size_t>(i)] += random_int(generator, -4, 4) * ulp;
    }
    for (size_t i = period.size() - static_cast<size_t>(at_end); i + 1 < period.size(); ++i) {
      period[i] += random_int(generator, -4, 4) * ulp;
    }
  }
  return period;
}

/// A random knot vector of the given degree (open or periodic, see RandomKnotOptions).
inline KnotVector random_knot_vector(int degree, const RandomKnotOptions& options,
                                     std::mt19937& generator) {
  if (options.periodic) {
    return KnotVector::periodic(degree, random_period_knots(degree, options, generator));
  }
  const double start = random_real(generator, -3.0, 3.0);
  const double end = start + random_real(generator, 0.5, 4.0);
  const std::vector<double> interior =
      random_interior_knots(degree, start, end, options.extra_control_points, generator);
  std::vector<double> knots;
  // Unclamped ends: the knots outside the domain spread over the span next to it.
  const int at_start = options.clamped ? degree + 1 : random_int(generator, 1, degree + 1);
  const int at_end = options.clamped ? degree + 1 : random_int(generator, 1, degree + 1);
  for (int i = degree + 1 - at_start; i > 0; --i) {
    knots.push_back(start - 0.3 * i);
  }
  knots.insert(knots.end(), static_cast<size_t>(at_start), start);
  knots.insert(knots.end(), interior.begin(), interior.end());
  knots.insert(knots.end(), static_cast<size_t>(at_end), end);
  for (int i = 1; i <= degree + 1 - at_end; ++i) {
    knots.push_back(end + 0.3 * i);
  }
  return {degree, std::move(knots)};
}

/// Control points in [-1, 1]^3 and, if rational, weights log-uniform in [0.05, 20].
inline void random_net(int count, bool rational, std::mt19937& generator, Eigen::MatrixX3d& points,
                       Eigen::VectorXd& weights) {
  points.resize(count, 3);
  weights = Eigen::VectorXd::Ones(count);
  for (int i = 0; i < count; ++i) {
    points.row(i) << random_real(generator, -1, 1), random_real(generator, -1, 1),
        random_real(generator, -1, 1);
    if (rational) {
      weights[i] = 0.05 * std::pow(400.0, random_real(generator, 0.0, 1.0));
    }
  }
}

inline NurbsCurve random_curve(int degree, const RandomKnotOptions& options, bool rational,
                               std::mt19937& generator) {
  KnotVector knots = random_knot_vector(degree, options, generator);
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_net(knots.control_point_count(), rational, generator, points, weights);
  return {std::move(knots), std::move(points), std::move(weights)};
}

inline NurbsSurface random_surface(int degree_u, int degree_v, const RandomKnotOptions& options_u,
                                   const RandomKnotOptions& options_v, bool rational,
                                   std::mt19937& generator) {
  KnotVector knots_u = random_knot_vector(degree_u, options_u, generator);
  KnotVector knots_v = random_knot_vector(degree_v, options_v, generator);
  Eigen::MatrixX3d points;
  Eigen::VectorXd weights;
  random_net(knots_u.control_point_count() * knots_v.control_point_count(), rational, generator,
             points, weights);
  return {std::move(knots_u), std::move(knots_v), std::move(points), std::move(weights)};
}

/// The knot options of property-test trial `trial`: periodic every other trial (seam
/// multiplicity cycling through 1..degree, every other periodic list perturbed at the seam),
/// open ones clamped unless `allow_unclamped` and trial % 4 == 3.
inline RandomKnotOptions trial_options(int trial, int degree, bool allow_unclamped) {
  RandomKnotOptions options;
  options.periodic = trial % 2 == 0;
  options.seam_multiplicity = 1 + (trial / 2) % degree;
  options.perturb_seam = trial % 4 == 0;
  options.clamped = !(allow_unclamped && trial % 4 == 3);
  return options;
}

/// A knot to insert into `knots` (the seam given as the period end, the period start, an
/// existing knot or a random parameter) whose multiplicity is below the degree.
inline double random_knot_to_insert(const KnotVector& knots, std::mt19937& generator) {
  const double start = knots.domain_start();
  const double end = knots.domain_end();
  const std::vector<double> choices = {
      end, start, knots[random_int(generator, knots.degree(), knots.basis_count())],
      start + (end - start) * random_real(generator, 0.0, 1.0)};
  for (int attempt = random_int(generator, 0, 3);; attempt = 3) {
    const double u = choices[static_cast<size_t>(attempt)];
    const double wrapped = knots.wrap_to_period(u);
    if (knots.multiplicity(wrapped) < knots.degree()) {
      return u;
    }
  }
}

/// Parameters over the domain: `count` evenly spaced ones and every knot of the domain.
inline std::vector<double> test_parameters(const KnotVector& knots, int count) {
  const double start = knots.domain_start();
  const double end = knots.domain_end();
  std::vector<double> parameters;
  for (int i = 0; i <= count; ++i) {
    parameters.push_back(start + (end - start) * i / count);
  }
  for (const double knot : knots.knots()) {
    if (knot >= start && knot <= end) {
      parameters.push_back(knot);
    }
  }
  return parameters;
}

/// Largest |a(u) - b(u)| over test_parameters of a's knots, relative to the size of a's control
/// net (the largest coordinate magnitude). b is evaluated at the same u (periodic ones wrap).
inline double relative_deviation(const NurbsCurve& a, const NurbsCurve& b, int count = 64) {
  double worst = 0.0;
  for (const double u : test_parameters(a.knots(), count)) {
    worst = std::max(worst, (a.point(u) - b.point(u)).norm());
  }
  return worst / a.control_points().cwiseAbs().maxCoeff();
}

inline double relative_deviation(const NurbsSurface& a, const NurbsSurface& b, int count = 12) {
  double worst = 0.0;
  for (const double u : test_parameters(a.knots_u(), count)) {
    for (const double v : test_parameters(a.knots_v(), count)) {
      worst = std::max(worst, (a.point(u, v) - b.point(u, v)).norm());
    }
  }
  return worst / a.control_points().cwiseAbs().maxCoeff();
}

}  // namespace dnurbs::testing
