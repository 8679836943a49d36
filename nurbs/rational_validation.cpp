#include "dnurbs/nurbs/rational_validation.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

void check_control_points(const Eigen::MatrixX3d& control_points, int expected_count) {
  if (control_points.rows() != expected_count) {
    throw make_error("expected ", expected_count, " control points, got ", control_points.rows());
  }
  for (Eigen::Index i = 0; i < control_points.rows(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(control_points(i, c))) {
        throw make_error("control point ", i, " has a non-finite coordinate ", c, " (",
                         control_points(i, c), ")");
      }
    }
  }
}

void check_weights(const Eigen::VectorXd& weights, int expected_count) {
  if (weights.size() != expected_count) {
    throw make_error("expected ", expected_count, " weights, got ", weights.size());
  }
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights[i]) || !(weights[i] > 0.0)) {
      throw make_error("weight ", i, " is ", weights[i], "; weights must be finite and > 0");
    }
  }
}

}  // namespace dnurbs
