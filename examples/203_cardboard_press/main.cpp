// Cardboard pressed at its centre (Wu & de Melo, figure 4): resistance to metric variation and to
// curving (eta = 0.01, xi = 1e-8), border clamped, a normal force at the centre
// (spread over the 3 by 3 central nodes), with both
// normal approximations side by side (classic at x < 0, christoffel at x > 0). Writes
// frame_NNN.obj into argv[1].
// Usage: example_203_cardboard_press [OUTPUT_DIRECTORY [FRAMES]] (default cardboard_press/, 49
// frames).

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
  const auto out = examples::output_directory(argc, argv, "cardboard_press");
  const int frames = examples::count_argument(argc, argv, 49, "the number of frames");

  // A unit square of 17 by 17 nodes (h = 1/16).
  const Grid grid(17, 17, 1.0 / 16);
  TerzopoulosMaterial cardboard;
  cardboard.damping_density = 0.5;
  cardboard.eta << 0.01, 0.0, 0.0, 0.01;
  cardboard.xi << 1e-8, 1e-8, 1e-8, 1e-8;

  System system;
  for (const auto normal : {NormalApproximation::kClassic, NormalApproximation::kChristoffel}) {
    TerzopoulosSettings settings;
    settings.normal = normal;
    const double x0 = normal == NormalApproximation::kClassic ? -1.1 : 0.1;
    TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d(x0, 0, 0)), cardboard,
                             settings);
    sheet.fix_border();
    const int index = system.add_model(sheet);
    // The press: a ramped normal force on the 3 by 3 nodes around the centre.
    for (int j = 7; j <= 9; ++j) {
      for (int i = 7; i <= 9; ++i) {
        system.add_force(index, point_force(grid.parameter(i, j), [](double t) {
                           return Eigen::Vector3d(0, 0, -0.005 / 9 * std::min(t, 1.0));
                         }));
      }
    }
  }
  SemiImplicitStepper stepper;
  for (int frame = 0; frame < frames; ++frame) {
    std::vector<TriangleMesh> meshes;
    for (int m = 0; m < 2; ++m) {
      const auto& sheet = dynamic_cast<const TerzopoulosSurface&>(system.model(m));
      meshes.push_back(grid_triangle_mesh(grid, sheet.positions(system.coordinates(m)),
                                          m == 0 ? "classic" : "christoffel"));
    }
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_meshes(meshes, out / name);
    for (int s = 0; s < 10; ++s) {
      stepper.step(system, 0.005);
    }
  }
  const int centre = grid.index(8, 8);
  std::printf("cardboard: centre deflection classic %.4f, christoffel %.4f; frames in %s\n",
              system.coordinates(0)[3 * centre + 2], system.coordinates(1)[3 * centre + 2],
              out.string().c_str());
  return 0;
}
