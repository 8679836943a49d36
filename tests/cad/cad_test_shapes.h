#pragma once
// Shapes for the CAD exchange tests: batches of random curves and surfaces of every kind the
// exchange must carry (open clamped and unclamped, periodic with every seam multiplicity,
// rational or not), and the comparison of a shape with its copy read back from a file.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "dnurbs/nurbs/shape.h"
#include "tests/nurbs/random_shapes.h"

namespace dnurbs::testing {

/// A periodic basis with all the seam copies at the start of its period list, as Open CASCADE,
/// STEP and IGES carry it, and the shift k such that its control point i is control point
/// (i + k) mod n of `basis` (the same curve: the same bi-infinite knot sequence, numbered from
/// another knot). Open bases are returned as they are, with shift 0.
inline std::pair<KnotVector, int> seam_first_basis(const KnotVector& basis) {
  if (!basis.is_periodic()) {
    return {basis, 0};
  }
  std::vector<double> period = basis.period_knots();
  const auto at_start = static_cast<int>(std::count(period.begin(), period.end(), period.front()));
  const int seam = basis.multiplicity(basis.domain_start());
  const double end = period.back();
  std::vector<double> list(static_cast<size_t>(seam), period.front());
  for (const double knot : period) {
    if (knot != period.front() && knot != end) {
      list.push_back(knot);
    }
  }
  list.push_back(end);
  const int n = basis.control_point_count();
  return {KnotVector::periodic(basis.degree(), list), ((at_start - seam) % n + n) % n};
}

/// The shape with every periodic basis in seam-first form (seam_first_basis).
inline Shape seam_first_form(const Shape& shape) {
  if (const auto* curve = std::get_if<NurbsCurve>(&shape)) {
    const auto [knots, shift] = seam_first_basis(curve->knots());
    const int n = curve->control_point_count();
    Eigen::MatrixX3d points(n, 3);
    Eigen::VectorXd weights(n);
    for (int i = 0; i < n; ++i) {
      points.row(i) = curve->control_points().row((i + shift) % n);
      weights(i) = curve->weights()((i + shift) % n);
    }
    return NurbsCurve(knots, points, weights);
  }
  const NurbsSurface& surface = std::get<NurbsSurface>(shape);
  const auto [knots_u, shift_u] = seam_first_basis(surface.knots_u());
  const auto [knots_v, shift_v] = seam_first_basis(surface.knots_v());
  const int n_u = surface.control_point_count_u();
  const int n_v = surface.control_point_count_v();
  Eigen::MatrixX3d points(n_u * n_v, 3);
  Eigen::VectorXd weights(n_u * n_v);
  for (int i = 0; i < n_u; ++i) {
    for (int j = 0; j < n_v; ++j) {
      const int source = surface.control_point_index((i + shift_u) % n_u, (j + shift_v) % n_v);
      points.row(i * n_v + j) = surface.control_points().row(source);
      weights(i * n_v + j) = surface.weights()(source);
    }
  }
  return NurbsSurface(knots_u, knots_v, points, weights);
}

/// `count` random curves of degrees 1..5 (trial_options: periodic every other one, with every
/// seam multiplicity; open ones clamped or not), rational every third. Periodic ones are in
/// seam-first form (seam_first_form), the one form a file carries.
inline std::vector<Shape> random_exchange_curves(int count, std::mt19937& generator) {
  std::vector<Shape> shapes;
  for (int trial = 0; trial < count; ++trial) {
    const int degree = 1 + trial % 5;
    RandomKnotOptions options = trial_options(trial, degree, true);
    options.extra_control_points = 2;
    shapes.push_back(
        seam_first_form(Shape(random_curve(degree, options, trial % 3 != 1, generator))));
  }
  return shapes;
}

/// `count` random surfaces, periodic in u, in v, in both or neither, rational every other one,
/// in seam-first form.
inline std::vector<Shape> random_exchange_surfaces(int count, std::mt19937& generator) {
  std::vector<Shape> shapes;
  for (int trial = 0; trial < count; ++trial) {
    const int degree_u = 1 + trial % 4;
    const int degree_v = 1 + (trial + 2) % 5;
    RandomKnotOptions options_u = trial_options(trial, degree_u, true);
    RandomKnotOptions options_v = trial_options(trial / 2 + 1, degree_v, true);
    options_u.extra_control_points = 1;
    options_v.extra_control_points = 2;
    shapes.push_back(seam_first_form(Shape(
        random_surface(degree_u, degree_v, options_u, options_v, trial % 2 == 0, generator))));
  }
  return shapes;
}

/// Largest |a - b| over the entries, divided by the largest |a|.
inline double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return std::numeric_limits<double>::infinity();
  }
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, a.cwiseAbs().maxCoeff());
}

inline double relative_difference(const KnotVector& a, const KnotVector& b) {
  if (a.is_periodic() != b.is_periodic() || a.degree() != b.degree() || a.size() != b.size()) {
    return std::numeric_limits<double>::infinity();
  }
  const Eigen::Map<const Eigen::VectorXd> knots_a(a.knots().data(), a.size());
  const Eigen::Map<const Eigen::VectorXd> knots_b(b.knots().data(), b.size());
  return relative_difference(knots_a, knots_b);
}

/// Largest relative difference of the knots, weights and control points of two shapes (infinity
/// if they differ in kind, degree, periodicity or counts), and of their points at test
/// parameters.
struct ShapeDifference {
  double data = 0.0;
  double points = 0.0;
};

inline ShapeDifference shape_difference(const Shape& a, const Shape& b) {
  ShapeDifference difference;
  if (a.index() != b.index()) {
    return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }
  if (const auto* curve = std::get_if<NurbsCurve>(&a)) {
    const NurbsCurve& other = std::get<NurbsCurve>(b);
    difference.data =
        std::max({relative_difference(curve->knots(), other.knots()),
                  relative_difference(curve->weights(), other.weights()),
                  relative_difference(curve->control_points(), other.control_points())});
    if (std::isfinite(difference.data)) {
      for (const double u : test_parameters(curve->knots(), 16)) {
        difference.points =
            std::max(difference.points, relative_difference(curve->point(u), other.point(u)));
      }
    }
    return difference;
  }
  const NurbsSurface& surface = std::get<NurbsSurface>(a);
  const NurbsSurface& other = std::get<NurbsSurface>(b);
  difference.data =
      std::max({relative_difference(surface.knots_u(), other.knots_u()),
                relative_difference(surface.knots_v(), other.knots_v()),
                relative_difference(surface.weights(), other.weights()),
                relative_difference(surface.control_points(), other.control_points())});
  if (std::isfinite(difference.data)) {
    for (const double u : test_parameters(surface.knots_u(), 6)) {
      for (const double v : test_parameters(surface.knots_v(), 6)) {
        difference.points = std::max(difference.points,
                                     relative_difference(surface.point(u, v), other.point(u, v)));
      }
    }
  }
  return difference;
}

/// A fresh empty folder under the system's temporary folder.
inline std::filesystem::path fresh_cad_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() /
                         ("dnurbs_test_cad_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace dnurbs::testing
