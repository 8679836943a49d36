// A closed snake (Terzopoulos 2003, eqs. 1.2-1.13) finding the edge of a bright disk in a synthetic
// grey-scale image through the potential -|grad(G_sigma * I)|, stepped by eq 1.13 with one
// factorization. Writes frame_NNN.obj (the contour as an OBJ polyline) into argv[1].
// Usage: example_209_snake [OUTPUT_DIRECTORY [FRAMES]] (default snake/, 61 frames).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/snake.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "snake");
  const int frames = examples::count_argument(argc, argv, 61, "the number of frames");

  // A 96 by 96 image: an ellipse of semi-axes 30 and 20 pixels around (48, 48).
  Eigen::MatrixXd image = Eigen::MatrixXd::Zero(96, 96);
  for (int row = 0; row < 96; ++row) {
    for (int col = 0; col < 96; ++col) {
      image(row, col) = std::hypot((col - 48.0) / 30.0, (row - 48.0) / 20.0) < 1.0 ? 1.0 : 0.0;
    }
  }
  const int n = 60;
  NodePositions start = NodePositions::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n;
    start.row(i) << 48 + 38 * std::cos(angle), 48 + 32 * std::sin(angle), 0;
  }
  SnakeMaterial material;
  material.damping_density = 2.0;
  material.constant_tension = 2e-4;
  material.constant_rigidity = 1e-8;
  const Snake snake(NodeChain(n, true), start, material);
  System system(snake);
  system.add_force(0, potential_force(image_potential(image, 2.0, 20.0), 1e-3));
  Integrator integrator(IntegratorSettings{IntegratorScheme::kCentral});
  for (int frame = 0; frame < frames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    std::ofstream obj(out / name);
    const NodePositions r = snake.positions(system.coordinates(0));
    for (int i = 0; i < n; ++i) {
      obj << "v " << r(i, 0) << ' ' << r(i, 1) << ' ' << r(i, 2) << '\n';
    }
    obj << 'l';
    for (int i = 0; i <= n; ++i) {
      obj << ' ' << (i % n) + 1;
    }
    obj << '\n';
    for (int s = 0; s < 50; ++s) {
      integrator.step(system, 0.05);
    }
  }
  std::printf("snake: %d factorization(s); frames in %s\n", integrator.factorization_count(),
              out.string().c_str());
  return 0;
}
