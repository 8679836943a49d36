#include "dnurbs/surface/node_chain.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

NodeChain::NodeChain(int count, bool closed) : count_(count), closed_(closed) {
  const int minimum = closed ? 4 : 3;
  if (count < minimum) {
    throw make_error(closed ? "closed" : "open", " node chain of ", count,
                     " nodes has fewer than the ", minimum, " needed");
  }
}

int NodeChain::neighbor(int i, int offset) const {
  const int j = i + offset;
  if (closed_) {
    return ((j % count_) + count_) % count_;
  }
  return j >= 0 && j < count_ ? j : -1;
}

std::array<std::pair<int, double>, 2> NodeChain::linear_weights(double s) const {
  const double h = spacing();
  if (!std::isfinite(s)) {
    throw make_error("chain parameter s = ", s, " is not finite");
  }
  if (closed_) {
    double scaled = std::fmod(s / h, static_cast<double>(count_));
    if (scaled < 0.0) {
      scaled += count_;
    }
    const int i = std::min(static_cast<int>(std::floor(scaled)), count_ - 1);
    const double t = scaled - i;
    return {{{i, 1.0 - t}, {(i + 1) % count_, t}}};
  }
  const double scaled = std::clamp(s / h, 0.0, static_cast<double>(count_ - 1));
  const int i = std::min(static_cast<int>(std::floor(scaled)), count_ - 2);
  const double t = scaled - i;
  return {{{i, 1.0 - t}, {i + 1, t}}};
}

}  // namespace dnurbs
