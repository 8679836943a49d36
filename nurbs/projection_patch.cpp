#include "dnurbs/nurbs/projection_patch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include <Eigen/Dense>

#include "dnurbs/nurbs/bernstein.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "dnurbs/nurbs/nearest_candidate.h"

namespace dnurbs {
namespace {

// Element i (an int index) of a std::array or std::vector.
template <typename Container>
auto& at(Container& container, int i) {
  return container[static_cast<size_t>(i)];
}

// Round-off allowance of a stationarity coefficient: sums of up to a few hundred products.
constexpr double kNoise = 1024.0 * std::numeric_limits<double>::epsilon();
// Halvings of a patch (the longer side each time) before a box is settled by its centre:
// 20 per direction, boxes of 1e-6 of the patch.
constexpr int kMaxLevel = 40;
constexpr int kMaxNewtonSteps = 50;

// Calls add(i, j, k, l, weight) for every coefficient pair of an (m1, n1) and an (m2, n2) net;
// `weight` is that of their product in the (m1 + m2, n1 + n2) net (Farouki & Rajan eq. 7 per
// direction).
template <typename Add>
void for_each_product(int m1, int n1, int m2, int n2, Add add) {
  // The weights along t, C(n1, j) C(n2, l) / C(n1 + n2, j + l), once for all (i, k).
  std::vector<double> along_t(static_cast<size_t>((n1 + 1) * (n2 + 1)));
  for (int j = 0; j <= n1; ++j) {
    for (int l = 0; l <= n2; ++l) {
      at(along_t, j * (n2 + 1) + l) = bernstein_product_weight(n1, j, n2, l);
    }
  }
  for (int i = 0; i <= m1; ++i) {
    for (int k = 0; k <= m2; ++k) {
      const double along_s = bernstein_product_weight(m1, i, m2, k);
      for (int j = 0; j <= n1; ++j) {
        for (int l = 0; l <= n2; ++l) {
          add(i, j, k, l, along_s * at(along_t, j * (n2 + 1) + l));
        }
      }
    }
  }
}

// True if every coefficient is beyond the noise on the same side of 0 (no zero in the box).
bool keeps_one_sign(const double* c, int count, double noise) {
  bool positive = true;
  bool negative = true;
  for (int i = 0; i < count; ++i) {
    positive = positive && c[i] > noise;
    negative = negative && c[i] < -noise;
  }
  return positive || negative;
}

bool within_noise(const double* c, int count, double noise) {
  for (int i = 0; i < count; ++i) {
    if (std::abs(c[i]) > noise) {
      return false;
    }
  }
  return true;
}

struct Interval {
  double low;
  double high;
};

Interval operator*(const Interval& a, const Interval& b) {
  const double p1 = a.low * b.low;
  const double p2 = a.low * b.high;
  const double p3 = a.high * b.low;
  const double p4 = a.high * b.high;
  return {std::min({p1, p2, p3, p4}), std::max({p1, p2, p3, p4})};
}

// Enclosure of the partial derivative of a (m, n) Bernstein net along s (or t): the hull of
// m (c_{i+1,j} - c_{i,j}) (the hodograph's coefficients).
Interval derivative_hull(const double* c, int m, int n, bool along_s) {
  const int steps = along_s ? m : n;
  if (steps == 0) {
    return {0.0, 0.0};
  }
  Interval hull{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (int i = 0; i <= m - (along_s ? 1 : 0); ++i) {
    for (int j = 0; j <= n - (along_s ? 0 : 1); ++j) {
      const double next = along_s ? c[(i + 1) * (n + 1) + j] : c[i * (n + 1) + j + 1];
      const double difference = steps * (next - c[i * (n + 1) + j]);
      hull = {std::min(hull.low, difference), std::max(hull.high, difference)};
    }
  }
  return hull;
}

// Halves an (m, n) net along s (or t) into `left` and `right` (de Casteljau per column or row).
void split_net(const double* c, int m, int n, bool along_s, double* left, double* right) {
  if (along_s) {
    for (int j = 0; j <= n; ++j) {
      split_bernstein_half(c + j, m, n + 1, left + j, right + j);
    }
  } else {
    for (int i = 0; i <= m; ++i) {
      const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(i) * (n + 1);
      split_bernstein_half(c + row, n, 1, left + row, right + row);
    }
  }
}

}  // namespace

ProjectionPatch::ProjectionPatch(const Eigen::MatrixXd& homogeneous, int degree_u, int degree_v,
                                 bool rational, const Eigen::Vector4d& range)
    : p_(degree_u), q_(degree_v), range_(range) {
  net_.resize(homogeneous.rows());
  for (Eigen::Index i = 0; i < homogeneous.rows(); ++i) {
    net_[static_cast<size_t>(i)] = homogeneous.row(i).transpose();
    const Eigen::Vector3d projected = net_[static_cast<size_t>(i)].head<3>() / homogeneous(i, 3);
    box_min_ = i == 0 ? projected : Eigen::Vector3d(box_min_.cwiseMin(projected));
    box_max_ = i == 0 ? projected : Eigen::Vector3d(box_max_.cwiseMax(projected));
  }
  build_nets(rational);
}

void ProjectionPatch::build_nets(bool rational) {
  const int p = p_;
  const int q = q_;
  const auto h = [&](int a, int b) -> const Eigen::Vector4d& { return at(net_, a * (q + 1) + b); };
  // Partial derivative nets of H: H_u of degree (p - 1, q), H_v of degree (p, q - 1).
  const auto derivative = [&](bool along_u, int a, int b) -> Eigen::Vector4d {
    return along_u ? Eigen::Vector4d(p * (h(a + 1, b) - h(a, b)))
                   : Eigen::Vector4d(q * (h(a, b + 1) - h(a, b)));
  };
  for (const bool along_u : {true, false}) {
    Net& net = along_u ? g_u_ : g_v_;
    const int dm = along_u ? p - 1 : p;  // degrees of the derivative net
    const int dn = along_u ? q : q - 1;
    // D = H' w - H w' (rational, degree (p + dm, q + dn)) or D = H' (polynomial, w = 1).
    const int d_m = rational ? p + dm : dm;
    const int d_n = rational ? q + dn : dn;
    std::vector<Eigen::Vector3d> d(static_cast<size_t>((d_m + 1) * (d_n + 1)),
                                   Eigen::Vector3d::Zero());
    if (rational) {
      for_each_product(dm, dn, p, q, [&](int i, int j, int k, int l, double weight) {
        const Eigen::Vector4d hd = derivative(along_u, i, j);
        at(d, (i + k) * (d_n + 1) + j + l) +=
            weight * (hd.head<3>() * h(k, l)[3] - h(k, l).head<3>() * hd[3]);
      });
    } else {
      for (int i = 0; i <= dm; ++i) {
        for (int j = 0; j <= dn; ++j) {
          at(d, i * (d_n + 1) + j) = derivative(along_u, i, j).head<3>();
        }
      }
    }
    // g = (H - w Q).D = e - Q.f with e = H.D and f = w D, degree (p + d_m, q + d_n).
    net.degree_s = p + d_m;
    net.degree_t = q + d_n;
    net.e.assign(static_cast<size_t>(net.size()), 0.0);
    net.f.assign(static_cast<size_t>(net.size()), Eigen::Vector3d::Zero());
    for_each_product(p, q, d_m, d_n, [&](int i, int j, int k, int l, double weight) {
      const Eigen::Vector3d& dk = at(d, k * (d_n + 1) + l);
      const int index = (i + k) * (net.degree_t + 1) + j + l;
      at(net.e, index) += weight * h(i, j).head<3>().dot(dk);
      at(net.f, index) += weight * h(i, j)[3] * dk;
    });
    for (size_t i = 0; i < net.e.size(); ++i) {
      net.e_magnitude = std::max(net.e_magnitude, std::abs(net.e[i]));
      net.f_magnitude = std::max(net.f_magnitude, net.f[i].norm());
    }
  }
}

double ProjectionPatch::lower_bound(const Eigen::Vector3d& query) const {
  return (query - query.cwiseMax(box_min_).cwiseMin(box_max_)).norm();
}

Eigen::Vector3d ProjectionPatch::corner(int i) const {
  const int a = i % 2 == 0 ? 0 : p_;
  const int b = i / 2 == 0 ? 0 : q_;
  const Eigen::Vector4d& h = at(net_, a * (q_ + 1) + b);
  return h.head<3>() / h[3];
}

PatchPoint ProjectionPatch::evaluate(double s, double t) const {
  BernsteinBasis basis_s;
  BernsteinBasis basis_t;
  bernstein_basis(p_, s, basis_s);
  bernstein_basis(q_, t, basis_t);
  // Homogeneous H and its derivatives: per row a the t-sums, then the s-sums.
  Eigen::Vector4d h = Eigen::Vector4d::Zero();
  Eigen::Vector4d hs = Eigen::Vector4d::Zero();
  Eigen::Vector4d ht = Eigen::Vector4d::Zero();
  Eigen::Vector4d hss = Eigen::Vector4d::Zero();
  Eigen::Vector4d hst = Eigen::Vector4d::Zero();
  Eigen::Vector4d htt = Eigen::Vector4d::Zero();
  for (int a = 0; a <= p_; ++a) {
    Eigen::Vector4d r0 = Eigen::Vector4d::Zero();
    Eigen::Vector4d r1 = Eigen::Vector4d::Zero();
    Eigen::Vector4d r2 = Eigen::Vector4d::Zero();
    for (int b = 0; b <= q_; ++b) {
      const Eigen::Vector4d& c = at(net_, a * (q_ + 1) + b);
      r0 += basis_t[0][static_cast<size_t>(b)] * c;
      r1 += basis_t[1][static_cast<size_t>(b)] * c;
      r2 += basis_t[2][static_cast<size_t>(b)] * c;
    }
    const auto index = static_cast<size_t>(a);
    h += basis_s[0][index] * r0;
    hs += basis_s[1][index] * r0;
    ht += basis_s[0][index] * r1;
    hss += basis_s[2][index] * r0;
    hst += basis_s[1][index] * r1;
    htt += basis_s[0][index] * r2;
  }
  // Quotient rule on S = H / w (Piegl & Tiller eq. 4.20).
  PatchPoint result;
  const double w = h[3];
  result.point = h.head<3>() / w;
  result.s = (hs.head<3>() - hs[3] * result.point) / w;
  result.t = (ht.head<3>() - ht[3] * result.point) / w;
  result.ss = (hss.head<3>() - 2.0 * hs[3] * result.s - hss[3] * result.point) / w;
  result.st = (hst.head<3>() - hs[3] * result.t - ht[3] * result.s - hst[3] * result.point) / w;
  result.tt = (htt.head<3>() - 2.0 * ht[3] * result.t - htt[3] * result.point) / w;
  return result;
}

bool ProjectionPatch::newton(const Eigen::Vector3d& query, Eigen::Vector2d& st) const {
  // Newton's method on the gradient of |S - Q|^2 / 2, [(S - Q).S_s, (S - Q).S_t], whose
  // Jacobian is the Hessian (Piegl & Tiller eq. 6.6), kept in the patch [0, 1]^2.
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    const PatchPoint value = evaluate(st.x(), st.y());
    const Eigen::Vector3d offset = value.point - query;
    const Eigen::Vector2d gradient(offset.dot(value.s), offset.dot(value.t));
    Eigen::Matrix2d hessian;
    hessian << value.s.squaredNorm() + offset.dot(value.ss),
        value.s.dot(value.t) + offset.dot(value.st), value.s.dot(value.t) + offset.dot(value.st),
        value.t.squaredNorm() + offset.dot(value.tt);
    const double determinant = hessian.determinant();
    if (!(std::abs(determinant) > 0.0) || !std::isfinite(determinant)) {
      return false;
    }
    const Eigen::Vector2d newton_step = hessian.inverse() * gradient;
    const Eigen::Vector2d next = (st - newton_step).cwiseMax(0.0).cwiseMin(1.0);
    // Converged when the Newton step itself is at round-off (steps of a few ulps may repeat
    // forever); a step cut by the patch's edge towards a zero outside is no convergence.
    if (!(newton_step.cwiseAbs().maxCoeff() > 1e-14)) {
      st = next;
      return true;
    }
    if (next == st) {
      return false;
    }
    st = next;
  }
  return false;
}

/// The subdivision of one query in one patch: nets of the boxes on a stack of levels.
struct ProjectionPatch::Search {
  const ProjectionPatch& patch;
  const Eigen::Vector3d& query;
  ProjectionVisitor& visitor;
  std::vector<double>& workspace;
  double bound = 0.0;           ///< the bound on the minimum (the visitor returns it)
  double absolute_slack = 0.0;  ///< added to the bound before pruning (ties)
  int& budget;                  ///< boxes the query may still halve (shared by its patches)
  double noise_u = 0.0;
  double noise_v = 0.0;

  /// A box's slot: the nets g_u and g_v, then the 4 homogeneous coordinates of its control net.
  int geometry_size() const { return (patch.p_ + 1) * (patch.q_ + 1); }
  int size() const { return patch.g_u_.size() + patch.g_v_.size() + 4 * geometry_size(); }
  double* slot(int level, int child) {
    return workspace.data() + static_cast<size_t>((2 * level + child) * size());
  }

  // A lower bound on the distance from the query to the box's surface piece, which lies in the
  // convex hull of its projected control points (positive weights): the larger of the distance
  // to their bounding box and, along the unit vector e from the query to their centroid, the
  // separation min_i e.(P_i - Q) (a separating-axis bound, tight when the piece lies beside the
  // query rather than around it).
  double lower_bound(const double* geometry) const {
    const int count = geometry_size();
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    constexpr size_t kMaxNet = static_cast<size_t>(kMaxDegree + 1) * (kMaxDegree + 1);
    std::array<Eigen::Vector3d, kMaxNet> projected;
    for (int i = 0; i < count; ++i) {
      const double w = geometry[3 * count + i];
      Eigen::Vector3d& point = projected[static_cast<size_t>(i)];
      point =
          Eigen::Vector3d(geometry[i], geometry[count + i], geometry[2 * count + i]) / w - query;
      low = low.cwiseMin(point);
      high = high.cwiseMax(point);
      centroid += point;
    }
    const double box = (low.cwiseMax(0.0) + (-high).cwiseMax(0.0)).norm();
    const double length = centroid.norm();
    if (!(length > 0.0)) {
      return box;
    }
    const Eigen::Vector3d direction = centroid / length;
    double separation = std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i) {
      separation = std::min(separation, direction.dot(projected[static_cast<size_t>(i)]));
    }
    return std::max(box, separation);
  }

  // True if the control polygons of the box run longer along s than along t.
  bool longer_along_s(const double* geometry) const {
    const int count = geometry_size();
    const int p = patch.p_;
    const int q = patch.q_;
    const auto point = [&](int i, int j) -> Eigen::Vector3d {
      const int k = i * (q + 1) + j;
      return Eigen::Vector3d(geometry[k], geometry[count + k], geometry[2 * count + k]) /
             geometry[3 * count + k];
    };
    double along_s = 0.0;
    double along_t = 0.0;
    for (int i = 0; i <= p; ++i) {
      for (int j = 0; j <= q; ++j) {
        along_s = std::max(along_s, i < p ? (point(i + 1, j) - point(i, j)).norm() * p : 0.0);
        along_t = std::max(along_t, j < q ? (point(i, j + 1) - point(i, j)).norm() * q : 0.0);
      }
    }
    return along_s >= along_t;
  }

  bool pruned(double lower) const {
    return lower > bound * (1.0 + kProjectionTieTolerance) + absolute_slack;
  }

  // The box's corners are control points, exactly on the surface: they bound the minimum.
  void visit_corners(const double* geometry) {
    const int count = geometry_size();
    for (int corner = 0; corner < 4; ++corner) {
      const int i =
          (corner % 2 == 0 ? 0 : patch.p_) * (patch.q_ + 1) + (corner / 2 == 0 ? 0 : patch.q_);
      const double w = geometry[3 * count + i];
      const Eigen::Vector3d point(geometry[i] / w, geometry[count + i] / w,
                                  geometry[2 * count + i] / w);
      const double distance = (point - query).norm();
      if (distance < bound) {
        bound = visitor.surface_point(distance);
      }
    }
  }

  /// What the Krawczyk test says about the zeros of G = (g_u, g_v) in a box: none, exactly one,
  /// at most one (J(X) nonsingular, but K not inside X: e.g. a zero on the box's edge), unknown.
  enum class Zeros { kNone, kOne, kAtMostOne, kUnknown };

  // Krawczyk's test (Krawczyk, Newton-Algorithmen zur Bestimmung von Nullstellen mit
  // Fehlerschranken, Computing 4, 1969; Moore, A test for existence of solutions to nonlinear
  // systems, SIAM J. Numer. Anal. 14, 1977) on the box X = [0, 1]^2 of the nets: with J(X) the
  // interval hull of the Jacobian (from the nets' hodographs), Y ~ mid J(X)^-1 and c the centre,
  // K = c - Y G(c) + (I - Y J(X)) (X - c) holds every zero in X. K disjoint from X: no zero.
  // K inside X (up to a relative 1e-9) with J(X) nonsingular: one zero, to which
  // x <- x - Y G(x) converges. J(X) nonsingular alone: at most one zero (mean value theorem).
  Zeros krawczyk(const double* gu, const double* gv, Eigen::Matrix2d& y) const {
    const Net& u = patch.g_u_;
    const Net& v = patch.g_v_;
    const Interval a = derivative_hull(gu, u.degree_s, u.degree_t, true);
    const Interval b = derivative_hull(gu, u.degree_s, u.degree_t, false);
    const Interval c = derivative_hull(gv, v.degree_s, v.degree_t, true);
    const Interval d = derivative_hull(gv, v.degree_s, v.degree_t, false);
    const auto mid = [](const Interval& i) { return 0.5 * (i.low + i.high); };
    Eigen::Matrix2d middle;
    middle << mid(a), mid(b), mid(c), mid(d);
    const double determinant = middle.determinant();
    if (!(std::abs(determinant) > 0.0) || !std::isfinite(determinant)) {
      return Zeros::kUnknown;
    }
    y = middle.inverse();
    const Eigen::Vector2d g(bernstein_net_value(gu, u.degree_s, u.degree_t, 0.5, 0.5),
                            bernstein_net_value(gv, v.degree_s, v.degree_t, 0.5, 0.5));
    const Eigen::Vector2d centre = Eigen::Vector2d::Constant(0.5) - y * g;
    // Rows of I - Y J(X) as intervals; their magnitudes times |X - c| = 1/2 give the radius.
    const auto scaled = [](double factor, const Interval& i) {
      return factor >= 0.0 ? Interval{factor * i.low, factor * i.high}
                           : Interval{factor * i.high, factor * i.low};
    };
    const auto magnitude = [](double shift, const Interval& i1, const Interval& i2) {
      const double low = shift - i1.high - i2.high;
      const double high = shift - i1.low - i2.low;
      return std::max(std::abs(low), std::abs(high));
    };
    Eigen::Vector2d radius;
    for (int row = 0; row < 2; ++row) {
      const double m0 = magnitude(row == 0 ? 1.0 : 0.0, scaled(y(row, 0), a), scaled(y(row, 1), c));
      const double m1 = magnitude(row == 1 ? 1.0 : 0.0, scaled(y(row, 0), b), scaled(y(row, 1), d));
      // The nets' round-off (noise) enters through Y G.
      radius[row] = 0.5 * (m0 + m1) + std::abs(y(row, 0)) * noise_u + std::abs(y(row, 1)) * noise_v;
    }
    const Eigen::Vector2d low = centre - radius;
    const Eigen::Vector2d high = centre + radius;
    if ((high.array() < 0.0).any() || (low.array() > 1.0).any()) {
      return Zeros::kNone;
    }
    constexpr double kEdgeSlack = 1e-9;
    const bool inside =
        (low.array() >= -kEdgeSlack).all() && (high.array() <= 1.0 + kEdgeSlack).all();
    const Interval ad = a * d;
    const Interval bc = b * c;
    const bool injective = ad.low > bc.high || ad.high < bc.low;
    if (!injective) {
      return Zeros::kUnknown;
    }
    return inside ? Zeros::kOne : Zeros::kAtMostOne;
  }

  // The zero of a box that passed Krawczyk's test: the contraction x <- x - Y G(x) on the nets
  // (box coordinates, converging linearly), then Newton on the patch geometry from there
  // (quadratically, to round-off). Returns false if Newton did not converge near the box; `st`
  // is then the contraction's result.
  bool solve(const double* gu, const double* gv, const Eigen::Matrix2d& y, const Box& box,
             Eigen::Vector2d& st) const {
    const Net& u = patch.g_u_;
    const Net& v = patch.g_v_;
    Eigen::Vector2d x = Eigen::Vector2d::Constant(0.5);
    for (int step = 0; step < 100; ++step) {
      const Eigen::Vector2d g(bernstein_net_value(gu, u.degree_s, u.degree_t, x.x(), x.y()),
                              bernstein_net_value(gv, v.degree_s, v.degree_t, x.x(), x.y()));
      const Eigen::Vector2d next = x - y * g;
      const double change = (next - x).cwiseAbs().maxCoeff();
      x = next;
      if (!(change > 1e-12)) {
        break;
      }
    }
    st = Eigen::Vector2d(box.s0 + x.x() * (box.s1 - box.s0), box.t0 + x.y() * (box.t1 - box.t0))
             .cwiseMax(0.0)
             .cwiseMin(1.0);
    Eigen::Vector2d polished = st;
    if (patch.newton(query, polished) && inside(polished, box, 1e-6)) {
      st = polished;
      return true;
    }
    return false;
  }

  // True if st lies in the box grown by `slack` times its size.
  static bool inside(const Eigen::Vector2d& st, const Box& box, double slack) {
    const double margin = slack * std::max(box.s1 - box.s0, box.t1 - box.t0);
    return st.x() >= box.s0 - margin && st.x() <= box.s1 + margin && st.y() >= box.t0 - margin &&
           st.y() <= box.t1 + margin;
  }

  void run(const double* nets, const Box& box, int level) {
    const Net& u = patch.g_u_;
    const Net& v = patch.g_v_;
    const double* gu = nets;
    const double* gv = nets + u.size();
    const double* geometry = gv + v.size();
    if (pruned(lower_bound(geometry))) {
      return;  // no point of the box is nearer than the best so far
    }
    visit_corners(geometry);
    // Exclusion: g_u or g_v keeps one sign, so the box has no stationary point.
    if (keeps_one_sign(gu, u.size(), noise_u) || keeps_one_sign(gv, v.size(), noise_v)) {
      return;
    }
    const Eigen::Vector2d centre(0.5 * (box.s0 + box.s1), 0.5 * (box.t0 + box.t1));
    // Both conditions vanish to round-off over the box: the distance is constant there.
    if (within_noise(gu, u.size(), noise_u) && within_noise(gv, v.size(), noise_v)) {
      bound = visitor.stationary_point(centre.x(), centre.y(), true);
      return;
    }
    --budget;
    Eigen::Matrix2d y;
    const Zeros zeros = krawczyk(gu, gv, y);
    if (zeros == Zeros::kNone) {
      return;
    }
    if (zeros == Zeros::kOne) {
      Eigen::Vector2d st;
      const bool exact = solve(gu, gv, y, box, st);
      bound = visitor.stationary_point(st.x(), st.y(), exact);
      return;
    }
    if (zeros == Zeros::kAtMostOne) {
      // Newton from the centre landing in the box (within a hair, for a zero on its edge, as
      // on a knot line or at a split) has found the box's only possible zero.
      Eigen::Vector2d st = centre;
      if (patch.newton(query, st) && inside(st, box, 1e-9)) {
        bound = visitor.stationary_point(st.x(), st.y(), true);
        return;
      }
    }
    if (level >= kMaxLevel || budget <= 0) {
      // Unresolved (a continuum of stationary points, or a nearly singular one): Newton from the
      // centre settles it if it converges, else the centre is reported as approximate.
      Eigen::Vector2d st = centre;
      const bool converged = patch.newton(query, st);
      bound = converged ? visitor.stationary_point(st.x(), st.y(), true)
                        : visitor.stationary_point(centre.x(), centre.y(), false);
      return;
    }
    // Halve the side along which the control net is longer (the piece's extent in space, not
    // in parameters: rational pieces can be very anisotropic); search the half with the smaller
    // lower bound first.
    const bool along_s = longer_along_s(geometry);
    double* left = slot(level + 1, 0);
    double* right = slot(level + 1, 1);
    split_net(gu, u.degree_s, u.degree_t, along_s, left, right);
    const int offset_v = u.size();
    split_net(gv, v.degree_s, v.degree_t, along_s, left + offset_v, right + offset_v);
    const int offset_h = offset_v + v.size();
    for (int c = 0; c < 4; ++c) {
      const int offset = offset_h + c * geometry_size();
      split_net(nets + offset, patch.p_, patch.q_, along_s, left + offset, right + offset);
    }
    const Box first =
        along_s ? Box{box.s0, centre.x(), box.t0, box.t1} : Box{box.s0, box.s1, box.t0, centre.y()};
    const Box second =
        along_s ? Box{centre.x(), box.s1, box.t0, box.t1} : Box{box.s0, box.s1, centre.y(), box.t1};
    if (lower_bound(right + offset_h) < lower_bound(left + offset_h)) {
      run(right, second, level + 1);
      run(left, first, level + 1);
    } else {
      run(left, first, level + 1);
      run(right, second, level + 1);
    }
  }
};

void ProjectionPatch::stationary_points(const Eigen::Vector3d& query, double bound,
                                        double absolute_slack, std::vector<double>& workspace,
                                        int& budget, ProjectionVisitor& visitor) const {
  Search search{*this, query, visitor, workspace, bound, absolute_slack, budget};
  workspace.resize(2 * (static_cast<size_t>(kMaxLevel) + 1) * static_cast<size_t>(search.size()));
  double* root = search.slot(0, 0);
  for (int i = 0; i < g_u_.size(); ++i) {
    root[i] = g_u_.e[static_cast<size_t>(i)] - query.dot(g_u_.f[static_cast<size_t>(i)]);
  }
  double* root_v = root + g_u_.size();
  for (int i = 0; i < g_v_.size(); ++i) {
    root_v[i] = g_v_.e[static_cast<size_t>(i)] - query.dot(g_v_.f[static_cast<size_t>(i)]);
  }
  double* geometry = root_v + g_v_.size();
  const int count = search.geometry_size();
  for (int i = 0; i < count; ++i) {
    for (int c = 0; c < 4; ++c) {
      geometry[c * count + i] = net_[static_cast<size_t>(i)][c];
    }
  }
  search.noise_u = kNoise * (g_u_.e_magnitude + query.norm() * g_u_.f_magnitude);
  search.noise_v = kNoise * (g_v_.e_magnitude + query.norm() * g_v_.f_magnitude);
  search.run(root, Box{0.0, 1.0, 0.0, 1.0}, 0);
}

}  // namespace dnurbs
