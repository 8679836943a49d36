#include "dnurbs/vision/mesh_topology.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

void check_indices(const Eigen::MatrixX3i& triangles, int vertex_count) {
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    if (triangles.row(f).minCoeff() < 0 || triangles.row(f).maxCoeff() >= vertex_count) {
      throw make_error("mesh triangle ", f, " indexes a vertex outside [0, ", vertex_count, ")");
    }
  }
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

}  // namespace

MeshTopology mesh_topology(const Eigen::MatrixX3i& triangles, int vertex_count) {
  check_indices(triangles, vertex_count);
  std::vector<std::pair<int, int>> edges;
  std::vector<int> parent(static_cast<std::size_t>(vertex_count));
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(static_cast<std::size_t>(vertex_count), 0);
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(f, k);
      const int b = triangles(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
      parent[static_cast<std::size_t>(find_root(parent, a))] = find_root(parent, b);
      used[static_cast<std::size_t>(a)] = 1;
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  MeshTopology topology;
  topology.vertices = vertex_count;
  topology.edges = static_cast<int>(edges.size());
  topology.triangles = static_cast<int>(triangles.rows());
  for (int v = 0; v < vertex_count; ++v) {
    topology.components +=
        (used[static_cast<std::size_t>(v)] != 0 && find_root(parent, v) == v) ? 1 : 0;
  }
  topology.euler_characteristic = topology.vertices - topology.edges + topology.triangles;
  return topology;
}

bool is_closed_oriented_manifold(const Eigen::MatrixX3i& triangles, int vertex_count,
                                 std::string* reason) {
  check_indices(triangles, vertex_count);
  const auto fail = [&](const std::string& why) {
    if (reason != nullptr) {
      *reason = why;
    }
    return false;
  };
  // Directed edges: each must appear once, with its reverse once.
  std::map<std::pair<int, int>, int> directed;
  // Around each vertex, the fan's "next" map: the triangle (a, b, c) at a links b -> c.
  std::vector<std::vector<std::pair<int, int>>> fan(static_cast<std::size_t>(vertex_count));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const int a = triangles(f, 0);
    const int b = triangles(f, 1);
    const int c = triangles(f, 2);
    if (a == b || b == c || c == a) {
      return fail("triangle " + std::to_string(f) + " repeats a vertex");
    }
    for (int k = 0; k < 3; ++k) {
      const int p = triangles(f, k);
      const int q = triangles(f, (k + 1) % 3);
      if (++directed[{p, q}] > 1) {
        return fail("directed edge " + std::to_string(p) + "->" + std::to_string(q) +
                    " is used twice (non-manifold or inconsistent orientation)");
      }
      fan[static_cast<std::size_t>(p)].emplace_back(q, triangles(f, (k + 2) % 3));
    }
  }
  for (const auto& [edge, count] : directed) {
    if (directed.find({edge.second, edge.first}) == directed.end()) {
      return fail("edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) +
                  " bounds one triangle only (open boundary)");
    }
  }
  for (int v = 0; v < vertex_count; ++v) {
    auto& links = fan[static_cast<std::size_t>(v)];
    if (links.empty()) {
      return fail("vertex " + std::to_string(v) + " is in no triangle");
    }
    // The links b -> c around v must form one cycle through all of them.
    std::sort(links.begin(), links.end());
    int current = links.front().first;
    for (std::size_t step = 0; step < links.size(); ++step) {
      const auto next = std::lower_bound(links.begin(), links.end(), std::make_pair(current, -1));
      if (next == links.end() || next->first != current) {
        return fail("vertex " + std::to_string(v) + " has a broken fan");
      }
      current = next->second;
      if (current == links.front().first && step + 1 < links.size()) {
        return fail("vertex " + std::to_string(v) + " joins two fans (pinched)");
      }
    }
    if (current != links.front().first) {
      return fail("vertex " + std::to_string(v) + " has an open fan");
    }
  }
  return true;
}

double enclosed_volume(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& triangles) {
  check_indices(triangles, static_cast<int>(vertices.rows()));
  double volume = 0.0;
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(triangles(f, 0));
    const Eigen::Vector3d b = vertices.row(triangles(f, 1));
    const Eigen::Vector3d c = vertices.row(triangles(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace dnurbs
