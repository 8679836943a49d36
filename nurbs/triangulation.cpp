#include "dnurbs/nurbs/triangulation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/simplex_spline.h"

namespace dnurbs {

namespace {

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32U) |
         static_cast<std::uint32_t>(b);
}

// Strict crossing of segments [a, b] and [c, d] (interiors meet in one point), with the
// orientation tests counted as zero within `tolerance` (a distance).
bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d, double tolerance) {
  auto side = [tolerance](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                          const Eigen::Vector2d& r) {
    const double s = signed_double_area(p, q, r);
    return std::abs(s) <= tolerance * (q - p).norm() ? 0 : (s > 0.0 ? 1 : -1);
  };
  return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

}  // namespace

Triangulation::Triangulation(Eigen::MatrixX2d vertices, Eigen::MatrixX3i triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  if (vertex_count() < 3 || triangle_count() < 1) {
    throw make_error("triangulation has ", vertex_count(), " vertices and ", triangle_count(),
                     " triangles; it needs at least 3 and 1");
  }
  for (int i = 0; i < vertex_count(); ++i) {
    if (!vertices_.row(i).allFinite()) {
      throw make_error("triangulation vertex ", i, " (", vertices_(i, 0), ", ", vertices_(i, 1),
                       ") is not finite");
    }
  }
  for (int t = 0; t < triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int v = triangles_(t, c);
      if (v < 0 || v >= vertex_count()) {
        throw make_error("triangle ", t, " corner ", c, " is vertex ", v, ", outside 0..",
                         vertex_count() - 1);
      }
      if (triangles_(t, (c + 1) % 3) == v) {
        throw make_error("triangle ", t, " repeats vertex ", v);
      }
    }
  }
  const Eigen::Vector2d extent = vertices_.colwise().maxCoeff() - vertices_.colwise().minCoeff();
  diameter_ = extent.norm();
  for (int t = 0; t < triangle_count(); ++t) {
    const Eigen::Vector2d a = corner(t, 0);
    const Eigen::Vector2d b = corner(t, 1);
    const Eigen::Vector2d c = corner(t, 2);
    const double twice_area = signed_double_area(a, b, c);
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (twice_area <= kDegenerateArea * longest) {
      throw make_error("triangle ", t, " (vertices ", triangles_(t, 0), ", ", triangles_(t, 1),
                       ", ", triangles_(t, 2), ") has signed area ", 0.5 * twice_area,
                       twice_area < 0.0 ? ": it is clockwise, triangles must be counter-clockwise"
                                        : ": it is degenerate");
    }
    domain_area_ += 0.5 * twice_area;
  }
  build_bins();
  check_geometry();
  build_connectivity();
}

void Triangulation::build_connectivity() {
  // Directed edges: each may appear once (twice means overlapping or flipped triangles).
  std::unordered_map<std::uint64_t, int> directed;  // (a, b) -> 3 t + e
  directed.reserve(3 * static_cast<size_t>(triangle_count()));
  for (int t = 0; t < triangle_count(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const int a = triangles_(t, (e + 1) % 3);
      const int b = triangles_(t, (e + 2) % 3);
      const auto [it, inserted] = directed.emplace(edge_key(a, b), 3 * t + e);
      if (!inserted) {
        throw make_error("edge (", a, ", ", b, ") is used in the same direction by triangles ",
                         it->second / 3, " and ", t,
                         ": the triangles overlap or are not consistently counter-clockwise");
      }
    }
  }
  neighbors_.assign(3 * static_cast<size_t>(triangle_count()), -1);
  boundary_next_.assign(static_cast<size_t>(vertex_count()), -1);
  boundary_previous_.assign(static_cast<size_t>(vertex_count()), -1);
  for (const auto& [key, slot] : directed) {
    const int a = static_cast<int>(key >> 32U);
    const int b = static_cast<int>(key & 0xFFFFFFFFU);
    const auto reverse = directed.find(edge_key(b, a));
    if (reverse != directed.end()) {
      neighbors_[static_cast<size_t>(slot)] = reverse->second / 3;
      continue;
    }
    if (boundary_next_[static_cast<size_t>(a)] >= 0) {
      throw make_error("boundary vertex ", a, " has two outgoing boundary edges (to ",
                       boundary_next_[static_cast<size_t>(a)], " and ", b,
                       "): the boundary must be simple closed polygons");
    }
    boundary_next_[static_cast<size_t>(a)] = b;
    boundary_previous_[static_cast<size_t>(b)] = a;
  }

  // Fans counter-clockwise: in triangle (i, a, b) the next triangle around i is across (i, b).
  std::vector<std::vector<int>> incident(static_cast<size_t>(vertex_count()));
  for (int t = 0; t < triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      incident[static_cast<size_t>(triangles_(t, c))].push_back(t);
    }
  }
  vertex_triangles_.assign(static_cast<size_t>(vertex_count()), {});
  for (int i = 0; i < vertex_count(); ++i) {
    const auto& around = incident[static_cast<size_t>(i)];
    if (around.empty()) {
      throw make_error("triangulation vertex ", i, " is used by no triangle");
    }
    int start = around.front();
    if (is_boundary_vertex(i)) {
      start = directed.at(edge_key(i, boundary_next_[static_cast<size_t>(i)])) / 3;
    }
    auto& fan = vertex_triangles_[static_cast<size_t>(i)];
    int t = start;
    while (t >= 0 && fan.size() <= around.size()) {
      fan.push_back(t);
      const int c = triangles_(t, 0) == i ? 0 : (triangles_(t, 1) == i ? 1 : 2);
      t = neighbor(t, (c + 1) % 3);
      if (t == start) {
        break;
      }
    }
    if (fan.size() != around.size()) {
      throw make_error("vertex ", i, " is shared by ", around.size(),
                       " triangles that do not form one fan (two parts of the domain touch at it)");
    }
  }
}

void Triangulation::build_bins() {
  box_min_ = vertices_.colwise().minCoeff().transpose();
  const Eigen::Vector2d extent =
      (vertices_.colwise().maxCoeff().transpose() - box_min_).cwiseMax(1e-300);
  const double per_side = std::sqrt(static_cast<double>(triangle_count()));
  const double aspect = std::sqrt(extent.x() / extent.y());
  // Clamped in double before the conversion: a domain 1e44 times longer than wide (a fuzzed
  // shape file) gives an aspect far beyond int, and NaN (an infinite extent) gives one bin
  const auto bin_count = [](double x) {
    return x >= 1024.0 ? 1024 : (x >= 1.0 ? static_cast<int>(x) : 1);
  };
  bins_x_ = bin_count(std::ceil(per_side * aspect));
  bins_y_ = bin_count(std::ceil(per_side / aspect));
  bin_size_ = extent.cwiseQuotient(Eigen::Vector2d(bins_x_, bins_y_));
  std::vector<std::vector<int>> bins(static_cast<size_t>(bins_x_ * bins_y_));
  for (int t = 0; t < triangle_count(); ++t) {
    Eigen::Vector2d lo = corner(t, 0);
    Eigen::Vector2d hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(corner(t, c));
      hi = hi.cwiseMax(corner(t, c));
    }
    visit_bins(lo, hi, [&](int bin) { bins[static_cast<size_t>(bin)].push_back(t); });
  }
  bin_start_.assign(1, 0);
  bin_triangles_.clear();
  for (const auto& bin : bins) {
    bin_triangles_.insert(bin_triangles_.end(), bin.begin(), bin.end());
    bin_start_.push_back(static_cast<int>(bin_triangles_.size()));
  }
}

template <typename Visit>
void Triangulation::visit_bins(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                               Visit visit) const {
  auto index = [&](double value, double origin, double size, int count) {
    return std::clamp(static_cast<int>(std::floor((value - origin) / size)), 0, count - 1);
  };
  const int x0 = index(lo.x(), box_min_.x(), bin_size_.x(), bins_x_);
  const int x1 = index(hi.x(), box_min_.x(), bin_size_.x(), bins_x_);
  const int y0 = index(lo.y(), box_min_.y(), bin_size_.y(), bins_y_);
  const int y1 = index(hi.y(), box_min_.y(), bin_size_.y(), bins_y_);
  for (int x = x0; x <= x1; ++x) {
    for (int y = y0; y <= y1; ++y) {
      visit(x * bins_y_ + y);
    }
  }
}

void Triangulation::check_geometry() const {
  // Conforming: no vertex inside another triangle or on an edge it does not end, and no two
  // edges cross (bins limit the pairs tested to nearby triangles).
  const double tolerance = 1e-12 * diameter_;
  std::vector<int> candidates;
  for (int t = 0; t < triangle_count(); ++t) {
    Eigen::Vector2d lo = corner(t, 0);
    Eigen::Vector2d hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(corner(t, c));
      hi = hi.cwiseMax(corner(t, c));
    }
    candidates.clear();
    triangles_near_box(lo, hi, candidates);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (const int s : candidates) {
      if (s == t) {
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        const int v = triangles_(s, c);
        if (v != triangles_(t, 0) && v != triangles_(t, 1) && v != triangles_(t, 2) &&
            closed_contains(t, vertex(v), tolerance)) {
          throw make_error("vertex ", v, " (of triangle ", s, ") lies in triangle ", t,
                           ": the triangulation is not conforming (overlap or T-junction)");
        }
      }
      for (int e = 0; e < 3 && s > t; ++e) {
        for (int f = 0; f < 3; ++f) {
          if (segments_cross(corner(t, e), corner(t, (e + 1) % 3), corner(s, f),
                             corner(s, (f + 1) % 3), tolerance)) {
            throw make_error("an edge of triangle ", t, " crosses an edge of triangle ", s,
                             ": the triangles overlap");
          }
        }
      }
    }
  }
}

void Triangulation::triangles_near_box(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                       std::vector<int>& result) const {
  visit_bins(lo, hi, [&](int bin) {
    result.insert(result.end(), bin_triangles_.begin() + bin_start_[static_cast<size_t>(bin)],
                  bin_triangles_.begin() + bin_start_[static_cast<size_t>(bin) + 1]);
  });
}

Eigen::MatrixX2i Triangulation::boundary_edges() const {
  std::vector<int> starts;
  for (int i = 0; i < vertex_count(); ++i) {
    if (is_boundary_vertex(i)) {
      starts.push_back(i);
    }
  }
  Eigen::MatrixX2i edges(static_cast<Eigen::Index>(starts.size()), 2);
  for (size_t k = 0; k < starts.size(); ++k) {
    edges(static_cast<Eigen::Index>(k), 0) = starts[k];
    edges(static_cast<Eigen::Index>(k), 1) = boundary_next(starts[k]);
  }
  return edges;
}

double Triangulation::area(int t) const {
  return 0.5 * signed_double_area(corner(t, 0), corner(t, 1), corner(t, 2));
}

Eigen::Vector2d Triangulation::centroid(int t) const {
  return (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
}

Eigen::Vector3d Triangulation::barycentric(int t, const Eigen::Vector2d& u) const {
  const Eigen::Vector2d a = corner(t, 0);
  const Eigen::Vector2d b = corner(t, 1);
  const Eigen::Vector2d c = corner(t, 2);
  const double twice_area = signed_double_area(a, b, c);
  return Eigen::Vector3d(signed_double_area(u, b, c), signed_double_area(a, u, c),
                         signed_double_area(a, b, u)) /
         twice_area;
}

bool Triangulation::closed_contains(int t, const Eigen::Vector2d& u, double tolerance) const {
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector2d p = corner(t, e);
    const Eigen::Vector2d q = corner(t, (e + 1) % 3);
    if (signed_double_area(p, q, u) < -tolerance * (q - p).norm()) {
      return false;
    }
  }
  return true;
}

bool Triangulation::half_open_contains(int t, const Eigen::Vector2d& u, double tolerance) const {
  for (int e = 0; e < 3; ++e) {
    if (half_open_side(corner(t, e), corner(t, (e + 1) % 3), u, half_open_direction(), tolerance) <
        0) {
      return false;
    }
  }
  return true;
}

int Triangulation::locate(const Eigen::Vector2d& u) const {
  if (!u.allFinite()) {
    throw make_error("cannot locate the point (", u.x(), ", ", u.y(), "): it is not finite");
  }
  const double tolerance = kLocateTolerance * diameter_;
  const Eigen::Vector2d box_max =
      box_min_ + bin_size_.cwiseProduct(Eigen::Vector2d(bins_x_, bins_y_));
  if ((u.array() < box_min_.array() - tolerance).any() ||
      (u.array() > box_max.array() + tolerance).any()) {
    return -1;
  }
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(tolerance);
  std::vector<int> candidates;
  triangles_near_box(u - margin, u + margin, candidates);
  std::sort(candidates.begin(), candidates.end());
  int closed = -1;
  for (const int t : candidates) {
    if (!closed_contains(t, u, tolerance)) {
      continue;
    }
    if (half_open_contains(t, u, tolerance)) {
      return t;
    }
    if (closed < 0) {
      closed = t;
    }
  }
  return closed;
}

}  // namespace dnurbs
