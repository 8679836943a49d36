#pragma once
// Random conforming triangulations of the unit square for the tests of compliant_triangulation and
// restricted_mesh: a jittered grid, each cell cut by a random diagonal, random edge flips of
// convex quads, then random triangles with an edge on the boundary removed (an irregular boundary
// and odd triangle counts).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace dnurbs::testing {

struct Triangulation {
  Eigen::MatrixX2d uv;         // #V by 2, every vertex used
  Eigen::MatrixX3i triangles;  // #T by 3, counter-clockwise
};

inline double signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          const Eigen::Vector2d& c) {
  const Eigen::Vector2d e1 = b - a;
  const Eigen::Vector2d e2 = c - a;
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}

// For every undirected edge (a < b), the triangles that use it.
inline std::map<std::pair<int, int>, std::vector<int>> edge_triangles(
    const std::vector<std::array<int, 3>>& triangles) {
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[static_cast<size_t>(t)][static_cast<size_t>(k)];
      const int b = triangles[static_cast<size_t>(t)][static_cast<size_t>((k + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  }
  return edges;
}

inline Triangulation random_triangulation(int cells, int flips, int removals, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3 / cells, 0.3 / cells);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= cells; ++i) {
    for (int j = 0; j <= cells; ++j) {
      const bool interior_u = i > 0 && i < cells;
      const bool interior_v = j > 0 && j < cells;
      points.emplace_back(static_cast<double>(i) / cells + (interior_u ? jitter(random) : 0.0),
                          static_cast<double>(j) / cells + (interior_v ? jitter(random) : 0.0));
    }
  }
  auto index = [cells](int i, int j) { return i * (cells + 1) + j; };
  std::vector<std::array<int, 3>> triangles;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const int a = index(i, j);
      const int b = index(i + 1, j);
      const int c = index(i + 1, j + 1);
      const int d = index(i, j + 1);
      if (random() % 2 == 0) {
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
      } else {
        triangles.push_back({a, b, d});
        triangles.push_back({b, c, d});
      }
    }
  }
  // Flip random interior edges whose quad is convex (both new triangles keep a fair area)
  const double min_area = 0.05 / (cells * cells);
  for (int f = 0; f < flips; ++f) {
    const auto edges = edge_triangles(triangles);
    std::vector<std::pair<int, int>> interior;
    for (const auto& [edge, users] : edges) {
      if (users.size() == 2) {
        interior.push_back(edge);
      }
    }
    const std::pair<int, int> edge = interior[random() % interior.size()];
    const std::vector<int>& users = edges.at(edge);
    auto opposite = [&](int t) {
      for (const int v : triangles[static_cast<size_t>(t)]) {
        if (v != edge.first && v != edge.second) {
          return v;
        }
      }
      return -1;
    };
    const int c = opposite(users[0]);
    const int d = opposite(users[1]);
    const std::array<int, 3> first{c, d, edge.first};
    const std::array<int, 3> second{d, c, edge.second};
    auto area = [&](const std::array<int, 3>& t) {
      return signed_area(points[static_cast<size_t>(t[0])], points[static_cast<size_t>(t[1])],
                         points[static_cast<size_t>(t[2])]);
    };
    // Each new triangle counter-clockwise one way or the other; convex only if both areas are
    // large with opposite orientation of the two corner orders
    std::array<int, 3> t1 = first;
    std::array<int, 3> t2 = second;
    if (area(t1) < 0.0) {
      std::swap(t1[1], t1[2]);
    }
    if (area(t2) < 0.0) {
      std::swap(t2[1], t2[2]);
    }
    const double old_area = std::abs(area(triangles[static_cast<size_t>(users[0])])) +
                            std::abs(area(triangles[static_cast<size_t>(users[1])]));
    if (area(t1) > min_area && area(t2) > min_area &&
        std::abs(area(t1) + area(t2) - old_area) < 1e-12) {
      triangles[static_cast<size_t>(users[0])] = t1;
      triangles[static_cast<size_t>(users[1])] = t2;
    }
  }
  // Remove random triangles with a boundary edge
  for (int r = 0; r < removals; ++r) {
    const auto edges = edge_triangles(triangles);
    std::vector<int> on_boundary;
    for (const auto& [edge, users] : edges) {
      if (users.size() == 1) {
        on_boundary.push_back(users[0]);
      }
    }
    triangles.erase(triangles.begin() + on_boundary[random() % on_boundary.size()]);
  }
  // Keep the used vertices only, in their order
  std::vector<int> renumber(points.size(), -1);
  std::vector<Eigen::Vector2d> used;
  Triangulation result;
  result.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (size_t k = 0; k < 3; ++k) {
      int& slot = renumber[static_cast<size_t>(triangles[t][k])];
      if (slot < 0) {
        slot = static_cast<int>(used.size());
        used.push_back(points[static_cast<size_t>(triangles[t][k])]);
      }
      result.triangles(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(k)) = slot;
    }
  }
  result.uv.resize(static_cast<Eigen::Index>(used.size()), 2);
  for (size_t v = 0; v < used.size(); ++v) {
    result.uv.row(static_cast<Eigen::Index>(v)) = used[v].transpose();
  }
  return result;
}

}  // namespace dnurbs::testing
