#pragma once
// One Bezier patch of a NURBS surface prepared for closest-point queries: its homogeneous
// control net, the bounding box of the projected control points (a lower bound on the distance
// to any point of the patch, which lies in their convex hull for positive weights), and the
// Bernstein nets of the two stationarity conditions of |S - Q|^2, in which the patch's
// stationary points are isolated by subdivision with exclusion and uniqueness tests (Elber &
// Kim, Geometric constraint solver using multivariate rational spline functions, ACM Symposium
// on Solid Modeling and Applications 2001) and then found by Newton's method.

#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// S and its first and second partial derivatives at local (s, t) of a Bezier patch.
struct PatchPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Vector3d ss = Eigen::Vector3d::Zero();
  Eigen::Vector3d st = Eigen::Vector3d::Zero();
  Eigen::Vector3d tt = Eigen::Vector3d::Zero();
};

/// Receives what a patch search finds; each call returns the current bound on the minimum
/// distance (the search skips boxes farther than it).
class ProjectionVisitor {
 public:
  virtual ~ProjectionVisitor() = default;
  /// A stationary point of |S - Q|^2 at local (s, t): exact (Newton converged) or approximate
  /// (the centre of a box too small to resolve further).
  virtual double stationary_point(double s, double t, bool exact) = 0;
  /// Some point of the patch lies at `distance` from the query: the minimum is at most that.
  virtual double surface_point(double distance) = 0;
};

class ProjectionPatch {
 public:
  /// `homogeneous`: (p + 1)(q + 1) by 4 Bezier rows (w x, w y, w z, w), u index outer, of the
  /// span pair [u0, u1] x [v0, v1] = `range` (u0, u1, v0, v1). A polynomial patch (`rational`
  /// false) has w = 1. Precomputes the stationarity nets g_u = e_u - Q.f_u and g_v = e_v - Q.f_v
  /// with g_u = (H - w Q).(H_u w - H w_u) = w^3 (S - Q).S_u (and g_v likewise), of degree
  /// (3p - 1, 3q) and (3p, 3q - 1) when rational, (2p - 1, 2q) and (2p, 2q - 1) when not.
  ProjectionPatch(const Eigen::MatrixXd& homogeneous, int degree_u, int degree_v, bool rational,
                  const Eigen::Vector4d& range);

  /// (u0, u1, v0, v1).
  const Eigen::Vector4d& range() const { return range_; }
  /// Distance from `query` to the bounding box of the projected control points.
  double lower_bound(const Eigen::Vector3d& query) const;
  /// The corner (s, t) = (i % 2, i / 2) for i = 0..3: a control point, exactly on the surface.
  Eigen::Vector3d corner(int i) const;
  /// S and derivatives at local (s, t) in [0, 1]^2 (Bernstein basis, quotient rule P&T eq. 4.20).
  PatchPoint evaluate(double s, double t) const;

  /// Reports to `visitor` every stationary point of |S - Q|^2 in the closed patch that may be
  /// nearer than the bound (`bound` at first, then what the visitor returns). Boxes of the
  /// parameter square are skipped when the bounding box of their control net is farther than
  /// the bound (plus bound * kProjectionTieTolerance + absolute_slack) or when g_u or g_v keeps
  /// one sign on them; their corners (points of the patch) lower the bound. Krawczyk's interval
  /// Newton test excludes the other zero-free boxes and certifies boxes with exactly one zero,
  /// found by a contraction and Newton's method; the rest are halved along their longer side in
  /// space, down to 2^-40 of the patch's area or until `budget` (boxes halved, decremented,
  /// shared between the patches of a query) runs out; such a box is settled by Newton's method
  /// from its centre, or its centre is reported as approximate. `workspace` is scratch memory
  /// reused between calls.
  void stationary_points(const Eigen::Vector3d& query, double bound, double absolute_slack,
                         std::vector<double>& workspace, int& budget,
                         ProjectionVisitor& visitor) const;

 private:
  struct Net {
    int degree_s = 0;
    int degree_t = 0;
    std::vector<double> e;
    std::vector<Eigen::Vector3d> f;
    double e_magnitude = 0.0;
    double f_magnitude = 0.0;
    int size() const { return (degree_s + 1) * (degree_t + 1); }
  };
  struct Box {
    double s0, s1, t0, t1;
  };
  struct Search;

  void build_nets(bool rational);
  bool newton(const Eigen::Vector3d& query, Eigen::Vector2d& st) const;

  int p_ = 0;
  int q_ = 0;
  Eigen::Vector4d range_ = Eigen::Vector4d::Zero();
  /// (p + 1)(q + 1) homogeneous control points, u index outer.
  std::vector<Eigen::Vector4d> net_;
  Eigen::Vector3d box_min_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_max_ = Eigen::Vector3d::Zero();
  Net g_u_;
  Net g_v_;
};

}  // namespace dnurbs
