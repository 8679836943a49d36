#pragma once
// The running answer of a closest-point query: the nearest candidate so far, the rule that
// settles ties, and an upper bound on the minimum distance used for pruning.

#include <algorithm>
#include <limits>

#include <Eigen/Core>

namespace dnurbs {

/// Two candidate distances within kProjectionTieTolerance * (distance + size of the shape) of
/// each other are a tie: the smaller parameter wins (u, then v for surfaces). The tolerance
/// is a few hundred ulps, far below any distinct distance the tests compare (1e-10).
inline constexpr double kProjectionTieTolerance = 1e-13;

/// Parameter order of the tie rule: curves by u, surfaces by u then v.
inline bool parameter_less(double a, double b) {
  return a < b;
}
inline bool parameter_less(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
}

/// The nearest candidate of a query so far. Candidates are points where the minimum can be:
/// stationary points (exact when Newton converged, approximate when only a tiny box holds
/// them), ends and C^0 knots. Other points of the shape only lower `bound`, so that a
/// non-stationary point a hair from the true minimum (its distance equal to round-off) never
/// wins a tie against it.
template <typename Parameter>
struct NearestCandidate {
  double distance = std::numeric_limits<double>::infinity();
  Parameter parameter{};
  bool found = false;
  bool exact = false;
  /// Distance of some point of the shape: the minimum is at most this.
  double bound = std::numeric_limits<double>::infinity();
  /// Absolute part of the tie tolerance: kProjectionTieTolerance times the shape's size.
  double absolute_tie = 0.0;

  double tie() const { return kProjectionTieTolerance * distance + absolute_tie; }
  /// The bound the pruning tests use: nothing nearer than this can be lost.
  double pruning_bound() const {
    return std::min(bound, distance) * (1.0 + kProjectionTieTolerance) + absolute_tie;
  }
  void bound_by(double point_distance) { bound = std::min(bound, point_distance); }

  /// Takes the candidate if it is nearer by more than the tie tolerance, or ties and is exact
  /// with a smaller parameter (or the current one is only approximate). Approximate candidates
  /// must be strictly nearer.
  void offer(double candidate_distance, const Parameter& candidate_parameter, bool is_exact) {
    bound_by(candidate_distance);
    const bool nearer = !found || candidate_distance < distance - tie();
    const bool tie_won = found && is_exact && candidate_distance <= distance + tie() &&
                         (!exact || parameter_less(candidate_parameter, parameter));
    if (nearer || tie_won) {
      distance = candidate_distance;
      parameter = candidate_parameter;
      found = true;
      exact = is_exact;
    }
  }
};

}  // namespace dnurbs
