#include "dnurbs/surface/compliant_triangulation.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// A side of a triangle: the edge opposite corner k.
struct Side {
  int triangle = -1;
  int corner = -1;
};

std::uint64_t undirected_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

double signed_area(const Eigen::MatrixX2d& uv, int a, int b, int c) {
  const Eigen::Vector2d e1 = uv.row(b) - uv.row(a);
  const Eigen::Vector2d e2 = uv.row(c) - uv.row(a);
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}

// The triangles as counter-clockwise index triples, after checking indices and corners.
std::vector<std::array<int, 3>> counter_clockwise(const Eigen::MatrixX2d& uv,
                                                  const Eigen::MatrixX3i& triangles) {
  std::vector<std::array<int, 3>> result(static_cast<size_t>(triangles.rows()));
  for (int t = 0; t < triangles.rows(); ++t) {
    std::array<int, 3> v{triangles(t, 0), triangles(t, 1), triangles(t, 2)};
    for (const int index : v) {
      if (index < 0 || index >= uv.rows()) {
        throw make_error("compliant triangulation: triangle ", t, " has vertex ", index,
                         " outside [0, ", uv.rows(), ")");
      }
    }
    const double area = signed_area(uv, v[0], v[1], v[2]);
    if (!(area != 0.0)) {
      throw make_error("compliant triangulation: triangle ", t, " (", v[0], ", ", v[1], ", ", v[2],
                       ") has zero area in (u, v)");
    }
    if (area < 0.0) {
      std::swap(v[1], v[2]);
    }
    result[static_cast<size_t>(t)] = v;
  }
  return result;
}

// For every side, the side across it (triangle -1 on the boundary).
std::vector<std::array<Side, 3>> sides_across(const std::vector<std::array<int, 3>>& triangles) {
  std::unordered_map<std::uint64_t, std::array<Side, 2>> edges;
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    const std::array<int, 3>& v = triangles[static_cast<size_t>(t)];
    for (int k = 0; k < 3; ++k) {
      const int a = v[static_cast<size_t>((k + 1) % 3)];
      const int b = v[static_cast<size_t>((k + 2) % 3)];
      std::array<Side, 2>& pair = edges[undirected_key(a, b)];
      const int slot = pair[0].triangle < 0 ? 0 : pair[1].triangle < 0 ? 1 : 2;
      if (slot == 2) {
        throw make_error("compliant triangulation: edge (", a, ", ", b, ") is shared by triangles ",
                         pair[0].triangle, ", ", pair[1].triangle, " and ", t);
      }
      pair[static_cast<size_t>(slot)] = Side{t, k};
    }
  }
  std::vector<std::array<Side, 3>> across(triangles.size());
  for (const auto& [key, pair] : edges) {
    if (pair[1].triangle >= 0) {
      across[static_cast<size_t>(pair[0].triangle)][static_cast<size_t>(pair[0].corner)] = pair[1];
      across[static_cast<size_t>(pair[1].triangle)][static_cast<size_t>(pair[1].corner)] = pair[0];
    }
  }
  return across;
}

// Edmonds' blossom algorithm: augments the matching `mate` (-1: exposed) of the graph `adjacency`
// along a shortest alternating path from every exposed vertex among `roots`, contracting odd
// cycles (blossoms) on the way.
class BlossomMatching {
 public:
  BlossomMatching(const std::vector<std::vector<int>>& adjacency, std::vector<int>& mate)
      : adjacency_(adjacency),
        mate_(mate),
        parent_(adjacency.size()),
        base_(adjacency.size()),
        in_tree_(adjacency.size()),
        in_blossom_(adjacency.size()) {}

  void augment_from(const std::vector<int>& roots) {
    for (const int root : roots) {
      if (mate_[static_cast<size_t>(root)] < 0) {
        int v = find_augmenting_path(root);
        while (v >= 0) {
          const int p = parent_[static_cast<size_t>(v)];
          const int next = mate_[static_cast<size_t>(p)];
          mate_[static_cast<size_t>(v)] = p;
          mate_[static_cast<size_t>(p)] = v;
          v = next;
        }
      }
    }
  }

 private:
  int lowest_common_ancestor(int a, int b) const {
    std::vector<bool> seen(adjacency_.size(), false);
    while (true) {
      a = base_[static_cast<size_t>(a)];
      seen[static_cast<size_t>(a)] = true;
      if (mate_[static_cast<size_t>(a)] < 0) {
        break;
      }
      a = parent_[static_cast<size_t>(mate_[static_cast<size_t>(a)])];
    }
    while (true) {
      b = base_[static_cast<size_t>(b)];
      if (seen[static_cast<size_t>(b)]) {
        return b;
      }
      b = parent_[static_cast<size_t>(mate_[static_cast<size_t>(b)])];
    }
  }

  void mark_path(int v, int blossom_base, int child) {
    while (base_[static_cast<size_t>(v)] != blossom_base) {
      const int m = mate_[static_cast<size_t>(v)];
      in_blossom_[static_cast<size_t>(base_[static_cast<size_t>(v)])] = true;
      in_blossom_[static_cast<size_t>(base_[static_cast<size_t>(m)])] = true;
      parent_[static_cast<size_t>(v)] = child;
      child = m;
      v = parent_[static_cast<size_t>(m)];
    }
  }

  int find_augmenting_path(int root) {
    std::fill(parent_.begin(), parent_.end(), -1);
    std::fill(in_tree_.begin(), in_tree_.end(), false);
    std::iota(base_.begin(), base_.end(), 0);
    std::vector<int> queue{root};
    in_tree_[static_cast<size_t>(root)] = true;
    for (size_t head = 0; head < queue.size(); ++head) {
      const int v = queue[head];
      for (const int to : adjacency_[static_cast<size_t>(v)]) {
        if (base_[static_cast<size_t>(v)] == base_[static_cast<size_t>(to)] ||
            mate_[static_cast<size_t>(v)] == to) {
          continue;
        }
        const int to_mate = mate_[static_cast<size_t>(to)];
        if (to == root || (to_mate >= 0 && parent_[static_cast<size_t>(to_mate)] >= 0)) {
          // An odd cycle: contract it into its base
          const int blossom_base = lowest_common_ancestor(v, to);
          std::fill(in_blossom_.begin(), in_blossom_.end(), false);
          mark_path(v, blossom_base, to);
          mark_path(to, blossom_base, v);
          for (size_t i = 0; i < adjacency_.size(); ++i) {
            if (in_blossom_[static_cast<size_t>(base_[i])]) {
              base_[i] = blossom_base;
              if (!in_tree_[i]) {
                in_tree_[i] = true;
                queue.push_back(static_cast<int>(i));
              }
            }
          }
        } else if (parent_[static_cast<size_t>(to)] < 0) {
          parent_[static_cast<size_t>(to)] = v;
          if (to_mate < 0) {
            return to;
          }
          in_tree_[static_cast<size_t>(to_mate)] = true;
          queue.push_back(to_mate);
        }
      }
    }
    return -1;
  }

  const std::vector<std::vector<int>>& adjacency_;
  std::vector<int>& mate_;
  std::vector<int> parent_;
  std::vector<int> base_;
  std::vector<bool> in_tree_;
  std::vector<bool> in_blossom_;
};

// The triangle rotated so that corner k is the apex.
std::array<int, 3> with_apex(const std::array<int, 3>& v, int k) {
  return {v[static_cast<size_t>(k)], v[static_cast<size_t>((k + 1) % 3)],
          v[static_cast<size_t>((k + 2) % 3)]};
}

CompliantTriangulation split_at_centroids(const Eigen::MatrixX2d& uv,
                                          const std::vector<std::array<int, 3>>& triangles) {
  CompliantTriangulation result;
  result.barycentric = true;
  const auto count = static_cast<Eigen::Index>(triangles.size());
  result.mesh.uv.resize(uv.rows() + count, 2);
  result.mesh.uv.topRows(uv.rows()) = uv;
  result.mesh.triangles.resize(3 * count, 3);
  for (Eigen::Index t = 0; t < count; ++t) {
    const std::array<int, 3>& v = triangles[static_cast<size_t>(t)];
    const auto centroid = static_cast<int>(uv.rows() + t);
    result.mesh.uv.row(centroid) = (uv.row(v[0]) + uv.row(v[1]) + uv.row(v[2])) / 3.0;
    for (int k = 0; k < 3; ++k) {
      // The child keeping input edge (v_k, v_k+1): apex the centroid, that edge its refinement edge
      result.mesh.triangles.row(3 * t + k) << centroid, v[static_cast<size_t>(k)],
          v[static_cast<size_t>((k + 1) % 3)];
    }
  }
  result.added_vertices = static_cast<int>(count);
  return result;
}

}  // namespace

CompliantTriangulation make_compliant(const Eigen::MatrixX2d& uv,
                                      const Eigen::MatrixX3i& triangles) {
  const std::vector<std::array<int, 3>> ccw = counter_clockwise(uv, triangles);
  const std::vector<std::array<Side, 3>> across = sides_across(ccw);
  const int count = static_cast<int>(ccw.size());
  // The dual graph: triangles 0..count-1, then one node per boundary side
  std::vector<std::vector<int>> adjacency(static_cast<size_t>(count));
  std::vector<Side> boundary_side;
  for (int t = 0; t < count; ++t) {
    for (int k = 0; k < 3; ++k) {
      const Side& other = across[static_cast<size_t>(t)][static_cast<size_t>(k)];
      if (other.triangle >= 0) {
        adjacency[static_cast<size_t>(t)].push_back(other.triangle);
      } else {
        boundary_side.push_back(Side{t, k});
      }
    }
  }
  std::vector<int> mate(static_cast<size_t>(count) + boundary_side.size(), -1);
  std::vector<int> all_triangles(static_cast<size_t>(count));
  std::iota(all_triangles.begin(), all_triangles.end(), 0);
  // Greedy pairs first (most of the matching, cheaply), then Edmonds on the triangles alone: the
  // most blocks without a split
  for (int t = 0; t < count; ++t) {
    for (const int n : adjacency[static_cast<size_t>(t)]) {
      if (mate[static_cast<size_t>(t)] < 0 && mate[static_cast<size_t>(n)] < 0) {
        mate[static_cast<size_t>(t)] = n;
        mate[static_cast<size_t>(n)] = t;
      }
    }
  }
  {
    BlossomMatching matching(adjacency, mate);
    matching.augment_from(all_triangles);
  }
  // Then the boundary sides as extra nodes: an augmenting path from a left-over triangle ends at
  // a boundary side (a path ending at another triangle would have augmented above), so the pairs
  // stay as many and the triangle at the path's end is halved across its boundary edge
  adjacency.resize(mate.size());
  for (size_t b = 0; b < boundary_side.size(); ++b) {
    const auto node = static_cast<int>(static_cast<size_t>(count) + b);
    adjacency[static_cast<size_t>(boundary_side[b].triangle)].push_back(node);
    adjacency[static_cast<size_t>(node)].push_back(boundary_side[b].triangle);
  }
  {
    BlossomMatching matching(adjacency, mate);
    matching.augment_from(all_triangles);
  }
  if (std::any_of(mate.begin(), mate.begin() + count, [](int m) { return m < 0; })) {
    return split_at_centroids(uv, ccw);
  }
  CompliantTriangulation result;
  std::vector<Eigen::Vector2d> added;
  std::vector<std::array<int, 3>> labelled;
  for (int t = 0; t < count; ++t) {
    const std::array<int, 3>& v = ccw[static_cast<size_t>(t)];
    const int m = mate[static_cast<size_t>(t)];
    if (m < count) {
      // A block: the common edge is the refinement edge of both
      for (int k = 0; k < 3; ++k) {
        if (across[static_cast<size_t>(t)][static_cast<size_t>(k)].triangle == m) {
          labelled.push_back(with_apex(v, k));
          break;
        }
      }
      result.paired_blocks += t < m ? 1 : 0;
      continue;
    }
    // Halve (x0, x1, x2) across its boundary edge x1-x2 at the midpoint c: the halves
    // (x1, c, x0) and (x2, x0, c) share their refinement edge x0-c
    const Side& side = boundary_side[static_cast<size_t>(m - count)];
    const std::array<int, 3> x = with_apex(v, side.corner);
    const auto c = static_cast<int>(uv.rows() + static_cast<Eigen::Index>(added.size()));
    added.emplace_back(0.5 * (uv.row(x[1]) + uv.row(x[2])).transpose());
    labelled.push_back({x[1], c, x[0]});
    labelled.push_back({x[2], x[0], c});
    ++result.boundary_splits;
  }
  result.added_vertices = static_cast<int>(added.size());
  result.mesh.uv.resize(uv.rows() + result.added_vertices, 2);
  result.mesh.uv.topRows(uv.rows()) = uv;
  for (size_t i = 0; i < added.size(); ++i) {
    result.mesh.uv.row(uv.rows() + static_cast<Eigen::Index>(i)) = added[i].transpose();
  }
  result.mesh.triangles.resize(static_cast<Eigen::Index>(labelled.size()), 3);
  for (size_t t = 0; t < labelled.size(); ++t) {
    for (size_t k = 0; k < 3; ++k) {
      result.mesh.triangles(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(k)) =
          labelled[t][k];
    }
  }
  return result;
}

CompliantTriangulation make_compliant_by_barycentric_split(const Eigen::MatrixX2d& uv,
                                                           const Eigen::MatrixX3i& triangles) {
  const std::vector<std::array<int, 3>> ccw = counter_clockwise(uv, triangles);
  sides_across(ccw);  // checks that the triangulation is conforming
  return split_at_centroids(uv, ccw);
}

int compliance_violations(const BlockTriangulation& triangulation) {
  const std::vector<std::array<int, 3>> ccw =
      counter_clockwise(triangulation.uv, triangulation.triangles);
  const std::vector<std::array<Side, 3>> across = sides_across(ccw);
  int violations = 0;
  for (int t = 0; t < static_cast<int>(ccw.size()); ++t) {
    violations += ccw[static_cast<size_t>(t)][1] != triangulation.triangles(t, 1) ? 1 : 0;
    // The refinement edge is the side opposite corner 0; across it, the neighbour's must be too
    const Side& other = across[static_cast<size_t>(t)][0];
    violations += other.triangle >= 0 && other.corner != 0 ? 1 : 0;
  }
  return violations;
}

}  // namespace dnurbs
