// The rest shape and plastic flow of the swung D-NURBS model (the file comment of
// dnurbs_swung_surface.h): the rest coordinates, their curves at the Gauss points, and the yield
// rule of dynamics/core/plastic_flow.h on the curves' control points.

#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"

namespace dnurbs {

void DNurbsSwungSurface::set_rest_shape(ConstVectorRef q_rest) {
  check_size(q_rest, "rest shape");
  for (Eigen::Index i = 0; i < q_rest.size(); ++i) {
    if (!std::isfinite(q_rest[i])) {
      throw make_error("rest shape: coordinate ", i, " is ", q_rest[i], " (not finite)");
    }
  }
  if (layout_.mode == WeightMode::kFree) {
    for (int index = 2; index < coordinate_count(); index += 3) {
      if (q_rest[index] < minimum_weight_) {
        throw make_error("rest shape: weight coordinate ", index, " is ", q_rest[index],
                         ", below the minimum weight ", minimum_weight_);
      }
    }
  }
  // Each curve's points and derivatives at its own Gauss points at q_r
  std::vector<PlanarCurveSample> profile;
  std::vector<PlanarCurveSample> trajectory;
  quadrature_samples(q_rest, profile, trajectory);
  rest_points_.profile.resize(profile.size());
  rest_points_.trajectory.resize(trajectory.size());
  for (size_t i = 0; i < profile.size(); ++i) {
    rest_points_.profile[i] = profile[i].point;
  }
  for (size_t j = 0; j < trajectory.size(); ++j) {
    rest_points_.trajectory[j] = trajectory[j].point;
  }
  if (separable_) {
    separable_forms_.set_rest(q_rest);
  }
  rest_coordinates_ = q_rest;
}

void DNurbsSwungSurface::set_plastic_flow(const std::optional<PlasticFlow>& flow) {
  if (flow) {
    check_plastic_flow(*flow);
    if (!has_rest_shape()) {
      set_rest_shape(initial_coordinates_);
    }
  }
  plastic_flow_ = flow;
}

int DNurbsSwungSurface::flow_rest_shape(ConstVectorRef q, double dt) {
  if (!plastic_flow_) {
    return 0;
  }
  check_size(q, "coordinate");
  // The nodes are the curves' control points, (x, z[, w]) and (X, Y[, W]) in the same stride
  Eigen::VectorXd rest = rest_coordinates_;
  const int yielded =
      flow_rest_positions(*plastic_flow_, dt, layout_.per_control_point, q, rest, 2);
  if (yielded > 0) {
    set_rest_shape(rest);
  }
  return yielded;
}

Eigen::VectorXd DNurbsSwungSurface::flowing_rest_coordinates() const {
  return plastic_flow_ ? rest_coordinates_ : Eigen::VectorXd();
}

void DNurbsSwungSurface::restore_flowing_rest_coordinates(ConstVectorRef rest) {
  if (!plastic_flow_) {
    Model::restore_flowing_rest_coordinates(rest);
  }
  set_rest_shape(rest);
}

}  // namespace dnurbs
