#include "dnurbs/dynamics/core/plastic_flow.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

void check_plastic_flow(const PlasticFlow& flow) {
  if (!(flow.yield >= 0.0) || !std::isfinite(flow.yield)) {
    throw make_error("plastic yield ", flow.yield, " is not a non-negative finite distance");
  }
  if (!(flow.rate > 0.0) || !std::isfinite(flow.rate)) {
    throw make_error("plastic rate ", flow.rate, " is not a positive finite number");
  }
}

int flow_rest_positions(const PlasticFlow& flow, double dt, int stride,
                        const Eigen::Ref<const Eigen::VectorXd>& q,
                        Eigen::Ref<Eigen::VectorXd> rest, int dimension) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw make_error("plastic flow: time step ", dt, " is not positive and finite");
  }
  if (dimension < 2 || dimension > 3) {
    throw make_error("plastic flow: a node position of ", dimension,
                     " coordinates (expected 2 or 3)");
  }
  if (stride < dimension || q.size() != rest.size() || q.size() % stride != 0) {
    throw make_error("plastic flow: ", q.size(), " coordinates and ", rest.size(),
                     " rest coordinates are not nodes of ", stride);
  }
  const double fraction = std::min(1.0, flow.rate * dt);
  int yielded = 0;
  for (Eigen::Index offset = 0; offset < q.size(); offset += stride) {
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1> strain =
        q.segment(offset, dimension) - rest.segment(offset, dimension);
    const double distance = strain.norm();
    if (distance > flow.yield) {
      rest.segment(offset, dimension) += (fraction * (distance - flow.yield) / distance) * strain;
      ++yielded;
    }
  }
  return yielded;
}

void check_rest_coordinates(const Eigen::Ref<const Eigen::VectorXd>& rest, Eigen::Index size) {
  if (rest.size() != size) {
    throw make_error("rest coordinates: ", rest.size(), " given, the model has ", size);
  }
  for (Eigen::Index i = 0; i < size; ++i) {
    if (!std::isfinite(rest[i])) {
      throw make_error("rest coordinate ", i, " is ", rest[i], ", not finite");
    }
  }
}

}  // namespace dnurbs
