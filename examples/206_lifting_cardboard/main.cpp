// Lifting a cardboard by its middle point (Wu & de Melo, figure 9): big resistance to stretching
// (eta = 1e-2) and curving (xi = 2e-6), Christoffel normal, lying on the ground under gravity; a
// growing upward force at the middle lifts it. The ground is met by projection with friction.
// Writes frame_NNN.obj into argv[1].
// Usage: example_206_lifting_cardboard [OUTPUT_DIRECTORY [FRAMES]] (default lifting_cardboard/, 61
// frames).

#include <cstdio>
#include <filesystem>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/obstacles.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/surface/grid.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "lifting_cardboard");
  const int frames = examples::count_argument(argc, argv, 61, "the number of frames");

  const Grid grid(17, 17, 1.0 / 16);  // a unit square on the ground z = 0
  TerzopoulosMaterial cardboard;
  cardboard.damping_density = 0.5;
  cardboard.eta << 1e-2, 0.0, 0.0, 1e-2;
  cardboard.xi << 2e-6, 2e-6, 2e-6, 2e-6;
  TerzopoulosSettings settings;
  settings.normal = NormalApproximation::kChristoffel;
  TerzopoulosSurface sheet(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), cardboard,
                           settings);
  System system(sheet);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -0.002)));
  // The lift on the 3 by 3 middle nodes: it passes the sheet's weight (0.002) at t = 1.
  for (int j = 7; j <= 9; ++j) {
    for (int i = 7; i <= 9; ++i) {
      system.add_force(0, point_force(grid.parameter(i, j), [](double t) {
                         return Eigen::Vector3d(0, 0, 0.002 / 9 * std::min(t, 3.0));
                       }));
    }
  }
  const std::vector<Obstacle> ground{GroundPlane{}};
  ContactSettings contact;
  contact.friction = 0.3;
  const std::vector<Eigen::Vector2d> points = grid.node_parameters();
  SemiImplicitStepper stepper;
  for (int frame = 0; frame < frames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_mesh(grid_triangle_mesh(grid, sheet.positions(system.coordinates(0)), "cardboard"),
                out / name);
    for (int s = 0; s < 10; ++s) {
      stepper.step(system, 0.005);
      project_contacts(system, 0, ground, points, contact);
    }
  }
  const NodePositions r = sheet.positions(system.coordinates(0));
  std::printf("lifting cardboard: middle at z = %.3f, corner at z = %.3f; frames in %s\n",
              r(grid.index(8, 8), 2), r(0, 2), out.string().c_str());
  return 0;
}
