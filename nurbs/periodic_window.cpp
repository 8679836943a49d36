#include "dnurbs/nurbs/periodic_window.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// Element i (an int index) of a std::array or std::vector.
template <typename Container>
auto& at(Container& container, int i) {
  return container[static_cast<size_t>(i)];
}

// Non-negative remainder of i modulo n.
int wrap_index(int i, int n) {
  const int remainder = i % n;
  return remainder < 0 ? remainder + n : remainder;
}

// First index of `value` in the sorted knots (the start of its group).
int first_index_of(const std::vector<double>& knots, double value) {
  return static_cast<int>(std::lower_bound(knots.begin(), knots.end(), value) - knots.begin());
}

}  // namespace

KnotsAndRows unwrap_periodic(const KnotVector& knots, const Eigen::MatrixXd& rows, int first,
                             int count) {
  if (!knots.is_periodic()) {
    throw make_error("unwrap_periodic needs a periodic knot vector");
  }
  const int p = knots.degree();
  const int n = knots.control_point_count();
  if (count < p + 1) {
    throw make_error("an open window of degree ", p, " needs at least ", p + 1,
                     " control points, got ", count);
  }
  if (rows.rows() != n) {
    throw make_error("periodic knot vector with ", n, " control points got ", rows.rows(),
                     " control rows");
  }
  std::vector<double> values(static_cast<size_t>(count + p + 1));
  for (int k = 0; k < count + p + 1; ++k) {
    values[static_cast<size_t>(k)] = knots.extended_knot(first + k);
  }
  Eigen::MatrixXd window_rows(count, rows.cols());
  for (int k = 0; k < count; ++k) {
    window_rows.row(k) = rows.row(wrap_index(first + k, n));
  }
  return {KnotVector(p, std::move(values)), std::move(window_rows)};
}

KnotsAndRows clamp_window(const KnotsAndRows& window) {
  const KnotVector& knots = window.knots;
  const int p = knots.degree();
  const double start = knots.domain_start();
  const double end = knots.domain_end();
  // Insert both domain ends up to multiplicity p (Piegl & Tiller A5.4).
  std::vector<double> inserted(static_cast<size_t>(std::max(0, p - knots.multiplicity(start))),
                               start);
  inserted.insert(inserted.end(), static_cast<size_t>(std::max(0, p - knots.multiplicity(end))),
                  end);
  const KnotsAndRows refined = refine_control_rows(knots, window.rows, inserted);
  const std::vector<double>& t = refined.knots.knots();
  // With t_g..t_{g+s-1} = start (s >= p), the basis functions from g + s - p - 1 on, restricted
  // to [start, end], are those of the clamped vector; likewise up to h - 1 for the first index h
  // of `end`.
  const int g = first_index_of(t, start);
  const int start_multiplicity = refined.knots.multiplicity(start);
  const int h = first_index_of(t, end);
  const int first_row = g + start_multiplicity - p - 1;
  const int count = h - first_row;
  std::vector<double> clamped(static_cast<size_t>(p) + 1, start);
  clamped.insert(clamped.end(), t.begin() + g + start_multiplicity, t.begin() + h);
  clamped.insert(clamped.end(), static_cast<size_t>(p) + 1, end);
  return {KnotVector(p, std::move(clamped)), refined.rows.middleRows(first_row, count)};
}

Eigen::MatrixXd wrap_periodic(const KnotsAndRows& window, const KnotVector& target) {
  const int p = target.degree();
  const int n = target.control_point_count();
  if (!target.is_periodic() || window.knots.degree() != p) {
    throw make_error("wrap_periodic needs a periodic target of the window's degree ",
                     window.knots.degree(), ", got degree ", p);
  }
  const std::vector<double>& u = window.knots.knots();
  const int last_basis = window.knots.basis_count() - 1;
  const double start = window.knots.domain_start();
  const double end = window.knots.domain_end();
  const double tolerance =
      kPeriodicSeamTolerance * std::max({std::abs(start), std::abs(end), end - start});
  const auto matches = [&](int j, int i) {
    for (int k = 0; k <= p + 1; ++k) {
      if (std::abs(at(u, j + k) - target.extended_knot(i + k)) > tolerance) {
        return false;
      }
    }
    return true;
  };
  Eigen::MatrixXd result(n, window.rows.cols());
  for (int i = p; i < p + n; ++i) {
    const double first_knot = target.extended_knot(i);
    bool found = false;
    for (int j = first_index_of(u, first_knot - tolerance);
         j <= last_basis && u[static_cast<size_t>(j)] <= first_knot + tolerance && !found; ++j) {
      // Only basis functions whose support lies in the window's domain represent the spline.
      const bool inside =
          u[static_cast<size_t>(j)] >= start - tolerance && at(u, j + p + 1) <= end + tolerance;
      if (inside && matches(j, i)) {
        result.row(i % n) = window.rows.row(j);
        found = true;
      }
    }
    if (!found) {
      throw make_error("periodic basis function ", i, " with knots from ", first_knot,
                       " has no match in the open window [", start, ", ", end, "]");
    }
  }
  return result;
}

}  // namespace dnurbs
