// Melting cheese (Wu & de Melo, figure 1): a Terzopoulos surface with no resistance to metric
// variation or curving (eta = xi = 0), its border fixed, under gravity. With no internal force
// the interior simply falls while the border holds: the deformation is all in the cells next to
// the fixed nodes. Writes frame_NNN.obj into the directory given as the first argument.
// Usage: example_201_melting_cheese [OUTPUT_DIRECTORY [FRAMES]] (default melting_cheese/, 61
// frames).

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

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "melting_cheese");
  const int frames = examples::count_argument(argc, argv, 61, "the number of frames");

  // A 16 by 16 slice of cheese on a 17 by 17 grid in grid units (h = 1).
  const Grid grid(17, 17, 1.0);
  TerzopoulosMaterial cheese;
  cheese.mass_density = 1.0;
  cheese.damping_density = 0.01;  // eta = xi = 0 (the defaults)
  TerzopoulosSurface slice(grid, flat_grid_positions(grid, Eigen::Vector3d(-8, -8, 0)), cheese);
  slice.fix_border();

  System system(slice);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1e-4)));
  SemiImplicitStepper stepper;
  for (int frame = 0; frame < frames; ++frame) {
    const NodePositions r = slice.positions(system.coordinates(0));
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_mesh(grid_triangle_mesh(grid, r, "cheese"), out / name);
    for (int s = 0; s < 5; ++s) {
      stepper.step(system, 1.0);
    }
  }
  std::printf("melting cheese: centre sagged to z = %.4f; frames in %s\n",
              system.coordinates(0)[3 * grid.index(8, 8) + 2], out.string().c_str());
  return 0;
}
