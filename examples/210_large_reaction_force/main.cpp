// A large reaction force with unnormalized and normalized normals (Wu & de Melo, figures 6 and
// 8): the clamped paper sheet of figures 5 and 7 (17 by 17 unit square, eta_ii = 0.1, xi = 1e-4,
// gamma = 0.5) is pressed at its centre by ten times their force (0.1 on the 3 by 3 middle
// nodes) for 2 s and released for 2 s, so that it springs back under its own reaction force
// with only normal forces ever applied. The Christoffel normal is taken unnormalized (|B_ij| = 1,
// figure 6) and normalized (eqs 24-26, delta = 0.5, figure 8). Writes <normal>_pressed.obj and
// <normal>_released.obj into argv[1] and prints the largest mirror asymmetry of the spring-back
// (max |d(g k) - g d(k)| over the square's mirrors, relative to the largest displacement).
// Usage: example_210_large_reaction_force [OUTPUT_DIRECTORY [STEPS]] (default
// large_reaction_force/, 400 steps of 0.005 s per phase).

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/surface/grid.h"
#include "examples/example_arguments.h"

namespace {

// How far a displacement field on a square grid is from the square's mirror symmetry, relative
// to the largest displacement (u -> -u, v -> -v and u <-> v).
double asymmetry(const dnurbs::Grid& grid, const dnurbs::NodePositions& d) {
  const int n = grid.nu();
  double worst = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::RowVector3d a = d.row(grid.index(i, j));
      worst = std::max(
          worst,
          (d.row(grid.index(n - 1 - i, j)) - Eigen::RowVector3d(-a.x(), a.y(), a.z())).norm());
      worst = std::max(
          worst,
          (d.row(grid.index(i, n - 1 - j)) - Eigen::RowVector3d(a.x(), -a.y(), a.z())).norm());
      worst = std::max(worst,
                       (d.row(grid.index(j, i)) - Eigen::RowVector3d(a.y(), a.x(), a.z())).norm());
    }
  }
  return worst / d.rowwise().norm().maxCoeff();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "large_reaction_force");
  const int steps = examples::count_argument(argc, argv, 400, "the number of steps per phase");

  const Grid grid(17, 17, 1.0 / 16);
  double spring_back[2] = {0.0, 0.0};
  int m = 0;
  for (const auto normal :
       {NormalApproximation::kChristoffelUnnormalized, NormalApproximation::kChristoffel}) {
    const std::string name = m == 0 ? "unnormalized" : "normalized";
    TerzopoulosMaterial paper;
    paper.damping_density = 0.5;
    paper.eta << 0.1, 0.0, 0.0, 0.1;
    paper.xi << 1e-4, 1e-4, 1e-4, 1e-4;
    TerzopoulosSettings settings;
    settings.normal = normal;
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), paper,
                             settings);
    sheet.fix_border();
    System system(sheet);
    for (int j = 7; j <= 9; ++j) {
      for (int i = 7; i <= 9; ++i) {
        system.add_force(0, point_force(grid.parameter(i, j), Eigen::Vector3d(0, 0, -0.1 / 9)));
      }
    }
    SemiImplicitStepper stepper;
    for (int s = 0; s < steps; ++s) {
      stepper.step(system, 0.005);
    }
    const double pressed = -sheet.positions(system.coordinates(0)).col(2).minCoeff();
    export_mesh(grid_triangle_mesh(grid, sheet.positions(system.coordinates(0)), "paper"),
                out / (name + "_pressed.obj"));
    system.clear_forces();
    for (int s = 0; s < steps; ++s) {
      stepper.step(system, 0.005);
      const NodePositions d = sheet.positions(system.coordinates(0)) - sheet.rest_positions();
      spring_back[m] = std::max(spring_back[m], asymmetry(grid, d));
    }
    export_mesh(grid_triangle_mesh(grid, sheet.positions(system.coordinates(0)), "paper"),
                out / (name + "_released.obj"));
    std::printf("%-12s pressed %.4f, spring-back asymmetry %.3f\n", name.c_str(), pressed,
                spring_back[m]);
    ++m;
  }
  std::printf("unnormalized / normalized spring-back asymmetry %.2f\n",
              spring_back[0] / spring_back[1]);
  return 0;
}
