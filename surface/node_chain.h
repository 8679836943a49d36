#pragma once
// 1-D chains of nodes, open or closed (Terzopoulos 2003, section 2.3: nodes u_i = v(i h), i =
// 0..N-1): the parameterization of snakes, kept apart from the node positions.

#include <array>
#include <utility>

#include <Eigen/Core>

namespace dnurbs {

/// N nodes on s in [0, 1]. Open: node i at s = i h with h = 1/(N-1) (Terzopoulos 2003,
/// section 2.3). Closed (cyclic): node i at s = i h with h = 1/N, node N wrapping to node 0.
class NodeChain {
 public:
  /// Throws Error naming the count if it is below 3 (open) or 4 (closed): the rigidity term
  /// needs three nodes, and a cycle of three has no pentadiagonal band.
  NodeChain(int count, bool closed);

  int count() const { return count_; }
  bool closed() const { return closed_; }
  double spacing() const { return closed_ ? 1.0 / count_ : 1.0 / (count_ - 1); }
  double parameter(int i) const { return i * spacing(); }
  /// The index of node i + offset, modulo N when closed; -1 past an open chain's ends.
  int neighbor(int i, int offset) const;
  /// The two nodes and linear weights that interpolate the point at s (clamped to [0, 1] when
  /// open, wrapped when closed).
  std::array<std::pair<int, double>, 2> linear_weights(double s) const;

 private:
  int count_;
  bool closed_;
};

}  // namespace dnurbs
