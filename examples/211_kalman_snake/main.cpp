// A Kalman snake (Terzopoulos & Szeliski, "Tracking with Kalman snakes", 1992; Terzopoulos 2003,
// section 2.4) tracking an ellipse that moves on a circle, breathes and turns through noisy
// frames: the sequence of scripts/generate_vision_data.py (contour_sequence, 96 x 96, intensity
// 0.2 + 0.6 inside, Gaussian noise of sigma 0.15), rendered here by pixel coverage. Every frame
// is one predict (the snake's equations of motion, eq 1.13), an edge search along the predicted
// normals and an update. Writes frame_NNN.obj (the tracked contour as an OBJ polyline) into
// argv[1] and prints the largest distance of a node from the true ellipse.
// Usage: example_211_kalman_snake [OUTPUT_DIRECTORY [FRAMES]] (default kalman_snake/, 20 frames).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "dnurbs/dynamics/grid/kalman_snake.h"
#include "dnurbs/vision/image.h"
#include "examples/example_arguments.h"

namespace {

constexpr double kPi = std::numbers::pi;

/// The ellipse of frame k of `frames`: centre, semi-axes and rotation.
struct Ellipse {
  Eigen::Vector2d centre;
  double a = 0.0;
  double b = 0.0;
  double rotation = 0.0;

  static Ellipse at(int k, int frames) {
    const double phase = 2.0 * kPi * k / frames;
    return {Eigen::Vector2d(48.0 + 14.0 * std::cos(phase), 48.0 + 10.0 * std::sin(phase)),
            18.0 + 3.0 * std::sin(2.0 * phase), 12.0 + 2.0 * std::cos(2.0 * phase), 0.3 * phase};
  }
  bool inside(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d local = Eigen::Rotation2Dd(-rotation) * (p - centre);
    return std::pow(local.x() / a, 2) + std::pow(local.y() / b, 2) <= 1.0;
  }
  /// `count` points counter-clockwise on the ellipse.
  dnurbs::Contour points(int count) const {
    dnurbs::Contour contour(count, 2);
    for (int i = 0; i < count; ++i) {
      const double t = 2.0 * kPi * i / count;
      contour.row(i) = (centre + Eigen::Rotation2Dd(rotation) *
                                     Eigen::Vector2d(a * std::cos(t), b * std::sin(t)))
                           .transpose();
    }
    return contour;
  }
};

/// The frame: pixel coverage of the ellipse on an 8 x 8 sub-grid, plus noise.
dnurbs::Image render(const Ellipse& ellipse, std::mt19937& random) {
  dnurbs::Image image(96, 96);
  std::normal_distribution<double> noise(0.0, 0.15);
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 96; ++x) {
      int count = 0;
      for (int b = 0; b < 8; ++b) {
        for (int a = 0; a < 8; ++a) {
          count += ellipse.inside(Eigen::Vector2d(x - 0.5 + (a + 0.5) / 8, y - 0.5 + (b + 0.5) / 8))
                       ? 1
                       : 0;
        }
      }
      image(x, y) = 0.2 + 0.6 * count / 64.0 + noise(random);
    }
  }
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "kalman_snake");
  const int frames = examples::count_argument(argc, argv, 20, "the number of frames");
  const int sequence = 20;  // one revolution of the ellipse in 20 frames

  // The snake starts on the first frame's ellipse, at rest; tension w1/h^2 = 4.8 and rigidity
  // w2/h^4 = 2.6 (mu/dt^2 = 1) keep the nodes spaced, white acceleration noise of 1 px/frame^2
  const int n = 40;
  const Contour rest = Ellipse::at(0, sequence).points(n);
  KalmanSnakeParameters parameters;
  parameters.tension = 3e-3;
  parameters.rigidity = 1e-6;
  parameters.acceleration_variance = 1.0;
  parameters.initial_velocity_variance = 9.0;
  KalmanSnake snake(rest, rest, Eigen::MatrixX2d::Zero(n, 2), parameters);
  EdgeSearchParameters search;
  search.width = 96;
  search.height = 96;

  std::mt19937 random(1);
  double largest = 0.0;
  for (int frame = 0; frame < frames; ++frame) {
    const Ellipse truth = Ellipse::at(frame, sequence);
    const int edges = snake.track(render(truth, random), search);
    const Contour tracked = snake.positions();
    const Contour dense = truth.points(3600);
    double frame_largest = 0.0;
    for (int i = 0; i < n; ++i) {
      frame_largest =
          std::max(frame_largest, (dense.rowwise() - tracked.row(i)).rowwise().norm().minCoeff());
    }
    largest = std::max(largest, frame_largest);
    std::printf(
        "frame %2d: %d of %d nodes found an edge, largest distance %.3f px, node 0's "
        "position sd %.3f px\n",
        frame, edges, n, frame_largest, std::sqrt(snake.node_covariance(0).trace() / 2));

    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    std::ofstream obj(out / name);
    for (int i = 0; i < n; ++i) {
      obj << "v " << tracked(i, 0) << ' ' << tracked(i, 1) << " 0\n";
    }
    obj << 'l';
    for (int i = 0; i <= n; ++i) {
      obj << ' ' << (i % n) + 1;
    }
    obj << '\n';
  }
  std::printf("kalman snake: largest distance %.3f px over %d frames; frames in %s\n", largest,
              frames, out.string().c_str());
  return 0;
}
