// A rubber sheet with fixed border under gravity for increasing resistance to metric variation
// (Wu & de Melo, figure 3: eta = 7e-7, 4e-6, 3e-5, 1e-2; xi = 0): the larger eta, the flatter the
// sheet. Writes eta_K.obj (the settled sheet for the K-th eta) into argv[1] and prints the sag.
// Usage: example_204_rubber_sheet [OUTPUT_DIRECTORY [STEPS]] (default rubber_sheet/, 4000 steps per
// sheet).

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
  const auto out = examples::output_directory(argc, argv, "rubber_sheet");
  const int steps = examples::count_argument(argc, argv, 4000, "the number of steps per sheet");

  const Grid grid(9, 9, 1.0);  // 8 by 8, grid units
  const double etas[] = {7e-7, 4e-6, 3e-5, 1e-2};
  for (int k = 0; k < 4; ++k) {
    TerzopoulosMaterial rubber;
    rubber.damping_density = 0.02;
    rubber.eta << etas[k], etas[k], etas[k], etas[k];
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d(-4, -4, 0)), rubber);
    sheet.fix_border();
    System system(sheet);
    system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1e-5)));
    SemiImplicitStepper stepper;
    for (int s = 0; s < steps; ++s) {  // 4000 steps, t = 20000: settled
      stepper.step(system, 5.0);
    }
    const NodePositions r = sheet.positions(system.coordinates(0));
    char name[32];
    std::snprintf(name, sizeof(name), "eta_%d.obj", k);
    export_mesh(grid_triangle_mesh(grid, r, "rubber"), out / name);
    std::printf("rubber sheet eta = %g: centre sag %.4f\n", etas[k], -r(grid.index(4, 4), 2));
  }
  return 0;
}
