// Paper with increasing resistance to curving under a force at its centre (Wu & de Melo, figures 5
// and 7): the classic normal with figure 5's xi (0, 8e-8, 3.6e-7, 7e-7) and the Christoffel
// normal with figure 7's xi (0, 5e-6, 3e-5, 1e-4). With the Christoffel normal the paper stays
// flatter as xi grows. Writes <normal>_K.obj into argv[1] and prints the maximum curvature.
// Usage: example_205_paper_curving [OUTPUT_DIRECTORY [STEPS]] (default paper_curving/, 400 steps
// per sheet).

#include <cstdio>
#include <filesystem>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/surface/grid.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "paper_curving");
  const int steps = examples::count_argument(argc, argv, 400, "the number of steps per sheet");

  const Grid grid(17, 17, 1.0 / 16);  // a unit square
  const double figure5[] = {0.0, 8e-8, 3.6e-7, 7e-7};
  const double figure7[] = {0.0, 5e-6, 3e-5, 1e-4};
  for (const auto normal : {NormalApproximation::kClassic, NormalApproximation::kChristoffel}) {
    const bool classic = normal == NormalApproximation::kClassic;
    for (int k = 0; k < 4; ++k) {
      const double xi = classic ? figure5[k] : figure7[k];
      TerzopoulosMaterial paper;
      paper.damping_density = 0.5;
      paper.eta << 0.1, 0.0, 0.0, 0.1;
      paper.xi << xi, xi, xi, xi;
      TerzopoulosSettings settings;
      settings.normal = normal;
      TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), paper,
                               settings);
      sheet.fix_border();
      System system(sheet);
      for (int j = 7; j <= 9; ++j) {
        for (int i = 7; i <= 9; ++i) {
          system.add_force(0, point_force(grid.parameter(i, j), Eigen::Vector3d(0, 0, -0.01 / 9)));
        }
      }
      SemiImplicitStepper stepper;
      for (int s = 0; s < steps; ++s) {
        stepper.step(system, 0.005);
      }
      char name[40];
      std::snprintf(name, sizeof(name), "%s_%d.obj", classic ? "classic" : "christoffel", k);
      export_mesh(grid_triangle_mesh(grid, sheet.positions(system.coordinates(0)), "paper"),
                  out / name);
      std::printf("%-11s xi = %-7g max |B| = %.3f\n", classic ? "classic" : "christoffel", xi,
                  sheet.tensors(system.coordinates(0)).curvature.cwiseAbs().maxCoeff());
    }
  }
  return 0;
}
