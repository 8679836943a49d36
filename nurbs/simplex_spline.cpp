#include "dnurbs/nurbs/simplex_spline.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// Relative collinearity threshold: |det(a, b, c)| <= kCollinear * (longest side)^2.
constexpr double kCollinear = 1e-12;

bool lexicographically_less(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
}

double longest_side_squared(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            const Eigen::Vector2d& c) {
  return std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
}

bool collinear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return std::abs(signed_double_area(a, b, c)) <= kCollinear * longest_side_squared(a, b, c);
}

std::vector<int> knots_of(std::uint32_t mask) {
  std::vector<int> result;
  for (int k = 0; mask != 0; ++k, mask >>= 1U) {
    if ((mask & 1U) != 0U) {
      result.push_back(k);
    }
  }
  return result;
}

}  // namespace

HalfOpenEdge::HalfOpenEdge(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  // The side is computed from the lexicographically smaller end, then flipped: the two
  // orientations of one edge give exactly opposite answers.
  const bool flip = lexicographically_less(q, p);
  origin = flip ? q : p;
  edge = (flip ? p : q) - origin;
  length = edge.norm();
  sign = flip ? -1.0 : 1.0;
}

int HalfOpenEdge::side(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                       double tolerance) const {
  const double cross = edge.x() * (u.y() - origin.y()) - edge.y() * (u.x() - origin.x());
  if (std::abs(cross) > tolerance * length) {
    return sign * cross > 0.0 ? 1 : -1;
  }
  // On the line (within the tolerance): the direction decides, then its perpendicular.
  const double along = edge.x() * direction.y() - edge.y() * direction.x();
  if (along != 0.0) {
    return sign * along > 0.0 ? 1 : -1;
  }
  const double across = edge.x() * direction.x() + edge.y() * direction.y();  // d_perp = (-dy, dx)
  return sign * across > 0.0 ? 1 : -1;
}

int half_open_side(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& u,
                   const Eigen::Vector2d& direction, double tolerance) {
  return HalfOpenEdge(p, q).side(u, direction, tolerance);
}

SimplexSplineSet::SimplexSplineSet(const Eigen::MatrixX2d& knots,
                                   const std::vector<std::uint32_t>& sets,
                                   const std::vector<int>& group)
    : knots_(knots), group_(group) {
  const int count = static_cast<int>(knots.rows());
  if (count > 32) {
    throw make_error("simplex spline set has ", count, " knots, at most 32 are supported");
  }
  if (!group_.empty() && static_cast<int>(group_.size()) != count) {
    throw make_error("simplex spline set has ", count, " knots but ", group_.size(),
                     " group indices");
  }
  if (!knots.allFinite()) {
    throw make_error("simplex spline set has a knot that is not finite");
  }
  const std::uint32_t all = count == 32 ? 0xFFFFFFFFU : ((1U << static_cast<unsigned>(count)) - 1U);
  std::unordered_map<std::uint32_t, int> index;
  for (size_t s = 0; s < sets.size(); ++s) {
    if (std::popcount(sets[s]) < 3 || (sets[s] & ~all) != 0U) {
      throw make_error("simplex spline knot set ", s, " (mask ", sets[s],
                       ") must name at least 3 of the ", count, " knots");
    }
    roots_.push_back(build(sets[s], index));
  }
}

void SimplexSplineSet::choose_triple(std::uint32_t mask, Node& node) const {
  const std::vector<int> members = knots_of(mask);
  auto point = [&](int k) -> Eigen::Vector2d { return knots_.row(k).transpose(); };
  // Candidates in order of preference: the last knot of each group (a DMS knot set minus one of
  // these is again a DMS knot set), then every knot from the highest index down.
  std::vector<int> preferred;
  if (!group_.empty()) {
    for (auto it = members.rbegin(); it != members.rend(); ++it) {
      const bool seen = std::any_of(preferred.begin(), preferred.end(), [&](int k) {
        return group_[static_cast<size_t>(k)] == group_[static_cast<size_t>(*it)];
      });
      if (!seen) {
        preferred.push_back(*it);
      }
    }
  }
  if (preferred.size() == 3 &&
      !collinear(point(preferred[0]), point(preferred[1]), point(preferred[2]))) {
    std::copy(preferred.begin(), preferred.end(), node.knot);
    return;
  }
  // Otherwise the triple of largest area: the barycentric coordinates of points near the set
  // stay small, which keeps the recurrence's cancellation small.
  const int n = static_cast<int>(members.size());
  double best = 0.0;
  for (int a = n - 1; a >= 2; --a) {
    for (int b = a - 1; b >= 1; --b) {
      for (int c = b - 1; c >= 0; --c) {
        const int ka = members[static_cast<size_t>(a)];
        const int kb = members[static_cast<size_t>(b)];
        const int kc = members[static_cast<size_t>(c)];
        const double area = std::abs(signed_double_area(point(ka), point(kb), point(kc)));
        if (area > best && !collinear(point(ka), point(kb), point(kc))) {
          best = area;
          node.knot[0] = ka;
          node.knot[1] = kb;
          node.knot[2] = kc;
        }
      }
    }
  }
  if (best > 0.0) {
    return;
  }
  node.knot[0] = -1;  // every knot on one line: the zero function
}

int SimplexSplineSet::build(std::uint32_t mask, std::unordered_map<std::uint32_t, int>& index) {
  const auto found = index.find(mask);
  if (found != index.end()) {
    return found->second;
  }
  Node node;
  node.mask = mask;
  node.degree = std::popcount(mask) - 3;
  auto point = [&](int k) -> Eigen::Vector2d { return knots_.row(k).transpose(); };
  const std::vector<int> members = knots_of(mask);
  node.box_min = node.box_max = point(members.front());
  for (const int k : members) {
    node.box_min = node.box_min.cwiseMin(point(k));
    node.box_max = node.box_max.cwiseMax(point(k));
  }
  int result = -1;
  if (node.degree == 0) {
    // Degree 0: chi_[v0, v1, v2) / |det| (corners stored counter-clockwise).
    const std::vector<int>& corners = members;
    const double det = signed_double_area(point(corners[0]), point(corners[1]), point(corners[2]));
    if (!collinear(point(corners[0]), point(corners[1]), point(corners[2]))) {
      node.knot[0] = corners[0];
      node.knot[1] = det > 0.0 ? corners[1] : corners[2];
      node.knot[2] = det > 0.0 ? corners[2] : corners[1];
      node.leaf_value = 1.0 / std::abs(det);
      for (int e = 0; e < 3; ++e) {
        node.edges[e] = HalfOpenEdge(point(node.knot[e]), point(node.knot[(e + 1) % 3]));
      }
      nodes_.push_back(node);
      result = static_cast<int>(nodes_.size()) - 1;
    }
  } else {
    choose_triple(mask, node);
    if (node.knot[0] >= 0) {
      // Children first (post-order keeps children before parents in nodes_).
      for (int l = 0; l < 3; ++l) {
        node.child[l] = build(mask & ~(1U << static_cast<unsigned>(node.knot[l])), index);
      }
      // mu_l(y | W) = det(y; w_l+1 - w_l+2 ...) / det(W): the change of lambda_l along y.
      const double det =
          signed_double_area(point(node.knot[0]), point(node.knot[1]), point(node.knot[2]));
      node.inverse_det = 1.0 / det;
      for (int l = 0; l < 3; ++l) {
        const Eigen::Vector2d edge = point(node.knot[(l + 2) % 3]) - point(node.knot[(l + 1) % 3]);
        // lambda_l = ((w_l+1 - u) x (w_l+2 - u)) / det: d/du = -(edge.y), d/dv = edge.x.
        node.mu_u[l] = -edge.y() * node.inverse_det;
        node.mu_v[l] = edge.x() * node.inverse_det;
      }
      nodes_.push_back(node);
      result = static_cast<int>(nodes_.size()) - 1;
    }
  }
  index.emplace(mask, result);
  return result;
}

void SimplexSplineSet::evaluate(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                                double tolerance, int order,
                                Eigen::Matrix<double, 6, Eigen::Dynamic>& result) const {
  std::vector<double> scratch;
  evaluate(u, direction, tolerance, order, result, scratch);
}

void SimplexSplineSet::evaluate(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                                double tolerance, int order,
                                Eigen::Matrix<double, 6, Eigen::Dynamic>& result,
                                std::vector<double>& scratch) const {
  if (order < 0 || order > 2) {
    throw make_error("simplex spline derivative order ", order, " is outside 0..2");
  }
  evaluate_nodes(u, direction, tolerance, order, scratch);
  const int per_node = derivative_count(order);
  result.setZero(6, static_cast<Eigen::Index>(roots_.size()));
  for (size_t s = 0; s < roots_.size(); ++s) {
    if (roots_[s] >= 0) {
      const double* value =
          &scratch[static_cast<size_t>(per_node) * static_cast<size_t>(roots_[s])];
      for (int r = 0; r < per_node; ++r) {
        result(r, static_cast<Eigen::Index>(s)) = value[r];
      }
    }
  }
}

void SimplexSplineSet::evaluate_derivatives(const Eigen::Vector2d& u,
                                            const Eigen::Vector2d& direction, double tolerance,
                                            int order, Eigen::MatrixXd& result,
                                            std::vector<double>& scratch) const {
  if (order < 0 || order > kMaxSimplexDerivativeOrder) {
    throw make_error("simplex spline derivative order ", order, " is outside 0..",
                     kMaxSimplexDerivativeOrder);
  }
  evaluate_nodes(u, direction, tolerance, order, scratch);
  const int per_node = derivative_count(order);
  result.setZero(per_node, static_cast<Eigen::Index>(roots_.size()));
  for (size_t s = 0; s < roots_.size(); ++s) {
    if (roots_[s] >= 0) {
      result.col(static_cast<Eigen::Index>(s)) = Eigen::Map<const Eigen::VectorXd>(
          &scratch[static_cast<size_t>(per_node) * static_cast<size_t>(roots_[s])], per_node);
    }
  }
}

void SimplexSplineSet::evaluate_nodes(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                                      double tolerance, int order,
                                      std::vector<double>& scratch) const {
  const int per_node = derivative_count(order);
  scratch.assign(static_cast<size_t>(per_node) * nodes_.size(), 0.0);
  // Nodes in graph order (children first). The value by Micchelli's recurrence, the derivative
  // d^(a+b) / du^a dv^b from the children's derivative of one order less:
  //   D_u D^(a-1,b) M(V) = m sum_l mu_l(e_u | W) D^(a-1,b) M(V \ w_l)   (a > 0),
  // likewise along v for a = 0.
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const Node& node = nodes_[i];
    double* out = &scratch[static_cast<size_t>(per_node) * i];
    // Outside the knots' bounding box the spline and its derivatives vanish.
    if (u.x() < node.box_min.x() - tolerance || u.y() < node.box_min.y() - tolerance ||
        u.x() > node.box_max.x() + tolerance || u.y() > node.box_max.y() + tolerance) {
      continue;
    }
    if (node.degree == 0) {
      bool inside = true;
      for (int e = 0; e < 3 && inside; ++e) {
        inside = node.edges[e].side(u, direction, tolerance) > 0;
      }
      out[0] = inside ? node.leaf_value : 0.0;
      continue;
    }
    const auto m = static_cast<double>(node.degree);
    for (int l = 0; l < 3; ++l) {
      if (node.child[l] < 0) {
        continue;
      }
      const double* child =
          &scratch[static_cast<size_t>(per_node) * static_cast<size_t>(node.child[l])];
      const Eigen::Vector2d a = knots_.row(node.knot[(l + 1) % 3]).transpose() - u;
      const Eigen::Vector2d b = knots_.row(node.knot[(l + 2) % 3]).transpose() - u;
      const double lambda = (a.x() * b.y() - a.y() * b.x()) * node.inverse_det;
      const double mu_u = m * node.mu_u[l];  // m mu_l(e_u | W)
      const double mu_v = m * node.mu_v[l];
      out[0] += lambda * child[0];
      for (int k = 1; k <= order; ++k) {
        const int first = k * (k + 1) / 2;     // (k, 0)
        const int previous = (k - 1) * k / 2;  // (k - 1, 0)
        for (int j = 0; j < k; ++j) {          // (k - j, j), a = k - j > 0
          out[first + j] += mu_u * child[previous + j];
        }
        out[first + k] += mu_v * child[previous + k - 1];  // (0, k) from (0, k - 1)
      }
    }
  }
}

}  // namespace dnurbs
