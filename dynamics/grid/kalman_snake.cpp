#include "dnurbs/dynamics/grid/kalman_snake.h"

#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/grid/snake.h"

namespace dnurbs {

namespace {

void require_positive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw make_error("Kalman snake ", name, " = ", value, " is not positive and finite");
  }
}

void require_non_negative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw make_error("Kalman snake ", name, " = ", value, " is not non-negative and finite");
  }
}

/// Throws Error naming `what` if `rows` is not #count by 2 or holds a non-finite entry.
void require_node_rows(const Eigen::MatrixX2d& rows, Eigen::Index count, const char* what) {
  if (rows.rows() != count) {
    throw make_error(what, " has ", rows.rows(), " rows for a snake of ", count, " nodes");
  }
  for (Eigen::Index i = 0; i < count; ++i) {
    if (!rows.row(i).allFinite()) {
      throw make_error(what, " of node ", i, " is not finite");
    }
  }
}

void require_search(const EdgeSearchParameters& search) {
  check_image_size(search.width, search.height, "Kalman snake edge search frame size");
  if (search.width < 2 || search.height < 2) {
    throw make_error("Kalman snake edge search frame size ", search.width, " by ", search.height,
                     " is under 2 by 2 pixels");
  }
  require_positive(search.half_window, "edge search half_window");
  require_positive(search.sample_step, "edge search sample_step");
  if (search.sample_step > search.half_window) {
    throw make_error("Kalman snake edge search sample_step = ", search.sample_step,
                     " exceeds half_window = ", search.half_window);
  }
  require_non_negative(search.min_edge_strength, "edge search min_edge_strength");
  require_positive(search.variance, "edge search variance");
}

/// The scalar stiffness of a closed snake with constant w1, w2: the Snake's (eqs 1.8-1.11,
/// h = 1/N, indices modulo N), N by N.
SparseMatrix closed_snake_stiffness(int n, double w1, double w2) {
  SnakeMaterial material;
  material.constant_tension = w1;
  material.constant_rigidity = w2;
  return Snake(NodeChain(n, true), NodePositions::Zero(n, 3), material).scalar().stiffness;
}

void symmetrize(Eigen::MatrixXd& matrix) {
  const Eigen::MatrixXd transpose = matrix.transpose();
  matrix = 0.5 * (matrix + transpose);
}

}  // namespace

KalmanSnake::KalmanSnake(const Contour& rest_shape, const Contour& initial_positions,
                         const Eigen::MatrixX2d& initial_velocities,
                         const KalmanSnakeParameters& parameters)
    : rest_shape_(rest_shape), parameters_(parameters) {
  const Eigen::Index n = rest_shape.rows();
  if (n < 3) {
    throw make_error("Kalman snake rest shape has ", n, " nodes, fewer than 3");
  }
  require_node_rows(rest_shape, n, "Kalman snake rest shape");
  require_node_rows(initial_positions, n, "Kalman snake initial position");
  require_node_rows(initial_velocities, n, "Kalman snake initial velocity");
  require_positive(parameters.mass, "mass mu");
  require_non_negative(parameters.damping, "damping gamma");
  require_non_negative(parameters.tension, "tension w1");
  require_non_negative(parameters.rigidity, "rigidity w2");
  require_positive(parameters.time_step, "time step dt");
  require_positive(parameters.acceleration_variance, "acceleration_variance");
  require_positive(parameters.initial_position_variance, "initial_position_variance");
  require_positive(parameters.initial_velocity_variance, "initial_velocity_variance");

  const int count = static_cast<int>(n);
  stiffness_ = closed_snake_stiffness(count, parameters.tension, parameters.rigidity);
  // The semi-implicit step of eq 1.13 with v = (u(t) - u(t - dt)) / dt:
  // (c1 I + K) u(t + dt) = c1 u(t) + c2 v(t) + K u_rest + mu a
  const double dt = parameters.time_step;
  const double mu = parameters.mass;
  const double c1 = mu / (dt * dt) + parameters.damping / (2.0 * dt);
  const double c2 = mu / dt - 0.5 * parameters.damping;
  Eigen::SparseMatrix<double> system(count, count);
  system.setIdentity();
  system = c1 * system + stiffness_;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factorization(system);
  const Eigen::MatrixXd inverse = factorization.solve(Eigen::MatrixXd::Identity(count, count));
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(count, count);

  transition_.resize(2 * n, 2 * n);
  transition_.topLeftCorner(n, n) = c1 * inverse;
  transition_.topRightCorner(n, n) = c2 * inverse;
  transition_.bottomLeftCorner(n, n) = (c1 * inverse - identity) / dt;
  transition_.bottomRightCorner(n, n) = (c2 / dt) * inverse;

  // The rest shape's force K u_rest (zero for a translation of the rest shape: K 1 = 0)
  const Eigen::MatrixX2d rest_response = inverse * (stiffness_ * rest_shape);
  offset_.resize(2 * n, 2);
  offset_.topRows(n) = rest_response;
  offset_.bottomRows(n) = rest_response / dt;

  // The acceleration noise enters as the force mu a: G = [mu B^-1; mu B^-1 / dt]
  Eigen::MatrixXd noise_gain(2 * n, n);
  noise_gain.topRows(n) = mu * inverse;
  noise_gain.bottomRows(n) = (mu / dt) * inverse;
  process_noise_ = parameters.acceleration_variance * noise_gain * noise_gain.transpose();

  state_.resize(2 * n, 2);
  state_.topRows(n) = initial_positions;
  state_.bottomRows(n) = initial_velocities;
  Eigen::VectorXd prior(2 * n);
  prior.head(n).setConstant(parameters.initial_position_variance);
  prior.tail(n).setConstant(parameters.initial_velocity_variance);
  covariance_ = prior.asDiagonal();
}

void KalmanSnake::predict() {
  state_ = transition_ * state_ + offset_;
  if (separable_) {
    covariance_ = transition_ * covariance_ * transition_.transpose() + process_noise_;
  } else {
    // A = I_2 (x) A_s is block diagonal over the axes: each 2N block P_ab <- A_s P_ab A_s^T
    const Eigen::Index m = transition_.rows();
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        Eigen::MatrixXd block =
            transition_ * covariance_.block(a * m, b * m, m, m) * transition_.transpose();
        if (a == b) {
          block += process_noise_;
        }
        covariance_.block(a * m, b * m, m, m) = block;
      }
    }
  }
  symmetrize(covariance_);
}

void KalmanSnake::update(const Contour& measured_positions, double variance) {
  const Eigen::Index n = node_count();
  require_node_rows(measured_positions, n, "Kalman snake measured position");
  require_positive(variance, "measurement variance");
  if (separable_) {
    update_separable(measured_positions, variance);
    return;
  }
  // The covariance couples the axes: the same measurements as rows (1, 0) and (0, 1) of H
  std::vector<NormalMeasurement> measurements;
  measurements.reserve(static_cast<std::size_t>(2 * n));
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      measurements.push_back(
          {static_cast<int>(i),
           axis == 0 ? Eigen::Vector2d::UnitX().eval() : Eigen::Vector2d::UnitY().eval(),
           measured_positions(i, axis), variance});
    }
  }
  update(measurements);
}

void KalmanSnake::update_separable(const Contour& measured_positions, double variance) {
  // H_s = [I, 0]: H_s P_s is P_s's first N rows and H_s P_s H_s^T + R its top-left block plus
  // variance I; one gain serves both axes.
  const Eigen::Index n = node_count();
  Eigen::MatrixXd innovation_covariance = covariance_.topLeftCorner(n, n);
  innovation_covariance.diagonal().array() += variance;
  const Eigen::LLT<Eigen::MatrixXd> factorization(innovation_covariance);
  const Eigen::MatrixXd measured_covariance = covariance_.topRows(n);
  // gain^T = S^-1 H P (N by 2N)
  const Eigen::MatrixXd gain_transpose = factorization.solve(measured_covariance);
  const Eigen::MatrixX2d innovation = measured_positions - state_.topRows(n);
  state_ += gain_transpose.transpose() * innovation;
  covariance_ -= measured_covariance.transpose() * gain_transpose;
  symmetrize(covariance_);
}

void KalmanSnake::update(const std::vector<NormalMeasurement>& measurements) {
  const int n = node_count();
  for (std::size_t j = 0; j < measurements.size(); ++j) {
    const NormalMeasurement& measurement = measurements[j];
    if (measurement.node < 0 || measurement.node >= n) {
      throw make_error("Kalman snake measurement ", j, " names node ", measurement.node,
                       " of a snake of ", n, " nodes");
    }
    if (!measurement.normal.allFinite() || std::abs(measurement.normal.norm() - 1.0) > 1e-9) {
      throw make_error("Kalman snake measurement ", j, " has normal (", measurement.normal.x(),
                       ", ", measurement.normal.y(), "), not a finite unit vector");
    }
    if (!std::isfinite(measurement.position)) {
      throw make_error("Kalman snake measurement ", j, " has position ", measurement.position);
    }
    require_positive(measurement.variance, "measurement variance");
  }
  if (measurements.empty()) {
    return;
  }
  make_coupled();
  // H (m by 4N): row j is normal^T on node j's (x, y), at state indices node and 2N + node
  const int m = static_cast<int>(measurements.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(2 * m));
  Eigen::VectorXd measured(m);
  Eigen::VectorXd variances(m);
  for (int j = 0; j < m; ++j) {
    const NormalMeasurement& measurement = measurements[static_cast<std::size_t>(j)];
    triplets.emplace_back(j, measurement.node, measurement.normal.x());
    triplets.emplace_back(j, 2 * n + measurement.node, measurement.normal.y());
    measured[j] = measurement.position;
    variances[j] = measurement.variance;
  }
  Eigen::SparseMatrix<double> H(m, 4 * n);
  H.setFromTriplets(triplets.begin(), triplets.end());
  // state_ is stored column by column: its 4N entries are the state in the axis-major order
  Eigen::Map<Eigen::VectorXd> state(state_.data(), 4 * static_cast<Eigen::Index>(n));
  const Eigen::MatrixXd HP = H * covariance_;
  Eigen::MatrixXd innovation_covariance = HP * H.transpose();
  innovation_covariance.diagonal() += variances;
  const Eigen::LLT<Eigen::MatrixXd> factorization(innovation_covariance);
  const Eigen::MatrixXd gain_transpose = factorization.solve(HP);
  const Eigen::VectorXd innovation = measured - H * state;
  state += gain_transpose.transpose() * innovation;
  covariance_ -= HP.transpose() * gain_transpose;
  symmetrize(covariance_);
}

int KalmanSnake::track(const Image& frame, const EdgeSearchParameters& search) {
  require_search(search);
  if (frame.width() != search.width || frame.height() != search.height) {
    throw make_error("Kalman snake frame is ", frame.width(), " by ", frame.height(),
                     " pixels, the sequence's frames ", search.width, " by ", search.height);
  }
  const ImageEdgePotential potential(frame, search.sigma, 1.0);
  predict();
  const std::vector<NormalMeasurement> measurements =
      edge_measurements(potential, positions(), search);
  update(measurements);
  return static_cast<int>(measurements.size());
}

void KalmanSnake::make_coupled() {
  if (!separable_) {
    return;
  }
  const Eigen::Index m = covariance_.rows();
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  full.topLeftCorner(m, m) = covariance_;
  full.bottomRightCorner(m, m) = covariance_;
  covariance_ = full;
  separable_ = false;
}

Contour KalmanSnake::positions() const {
  return state_.topRows(node_count());
}

Eigen::MatrixX2d KalmanSnake::velocities() const {
  return state_.bottomRows(node_count());
}

Eigen::MatrixXd KalmanSnake::covariance() const {
  if (!separable_) {
    return covariance_;
  }
  const Eigen::Index m = covariance_.rows();
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  full.topLeftCorner(m, m) = covariance_;
  full.bottomRightCorner(m, m) = covariance_;
  return full;
}

Eigen::Matrix2d KalmanSnake::node_covariance(int i) const {
  const int n = node_count();
  if (i < 0 || i >= n) {
    throw make_error("Kalman snake node ", i, " is not in [0, ", n, ")");
  }
  if (separable_) {
    return covariance_(i, i) * Eigen::Matrix2d::Identity();
  }
  const int y = 2 * n + i;
  Eigen::Matrix2d block;
  block << covariance_(i, i), covariance_(i, y), covariance_(y, i), covariance_(y, y);
  return block;
}

Eigen::MatrixX2d contour_normals(const Contour& contour) {
  const Eigen::Index n = contour.rows();
  Eigen::MatrixX2d normals = Eigen::MatrixX2d::Zero(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d tangent =
        (contour.row((i + 1) % n) - contour.row((i + n - 1) % n)).transpose();
    const double length = tangent.norm();
    if (length > 0.0) {
      normals.row(i) << -tangent.y() / length, tangent.x() / length;
    }
  }
  return normals;
}

std::vector<NormalMeasurement> edge_measurements(const ImageEdgePotential& potential,
                                                 const Contour& predicted,
                                                 const EdgeSearchParameters& search) {
  require_search(search);
  const Image& samples = potential.samples();
  if (samples.width() != search.width || samples.height() != search.height) {
    throw make_error("Kalman snake edge potential is ", samples.width(), " by ", samples.height(),
                     " pixels, the sequence's frames ", search.width, " by ", search.height);
  }
  const Eigen::MatrixX2d normals = contour_normals(predicted);
  const int steps = static_cast<int>(std::floor(search.half_window / search.sample_step));
  std::vector<double> strength(static_cast<std::size_t>(2 * steps + 1));
  std::vector<NormalMeasurement> measurements;
  for (Eigen::Index i = 0; i < predicted.rows(); ++i) {
    const Eigen::Vector2d node = predicted.row(i).transpose();
    const Eigen::Vector2d normal = normals.row(i).transpose();
    const bool inside = node.x() >= 0.0 && node.y() >= 0.0 && node.x() <= search.width - 1 &&
                        node.y() <= search.height - 1;
    if (!inside || normal.isZero()) {
      continue;
    }
    // |grad(G_sigma * I)| = -P (c = 1) along the normal; the strongest sample
    int best = 0;
    for (int j = 0; j <= 2 * steps; ++j) {
      const double offset = (j - steps) * search.sample_step;
      strength[static_cast<std::size_t>(j)] = -potential.value(node + offset * normal);
      if (strength[static_cast<std::size_t>(j)] > strength[static_cast<std::size_t>(best)]) {
        best = j;
      }
    }
    const auto at = [&](int j) { return strength[static_cast<std::size_t>(j)]; };
    if (best == 0 || best == 2 * steps || at(best) < search.min_edge_strength) {
      continue;
    }
    // The vertex of the parabola through the strongest sample and its neighbours
    const double curvature = at(best - 1) - 2.0 * at(best) + at(best + 1);
    const double vertex = curvature < 0.0 ? 0.5 * (at(best - 1) - at(best + 1)) / curvature : 0.0;
    const double offset = (best - steps + vertex) * search.sample_step;
    measurements.push_back(
        {static_cast<int>(i), normal, normal.dot(node) + offset, search.variance});
  }
  return measurements;
}

}  // namespace dnurbs
