// A table cloth falling on a table (Wu & de Melo, figure 2): eta_ii = 0.001, eta_12 = 0.0006, xi =
// 0, gravity, a box obstacle met by projection with friction. Prints the deepest penetration a step
// produced before projection. Writes frame_NNN.obj (cloth and table) into argv[1].
// Usage: example_202_table_cloth [OUTPUT_DIRECTORY [FRAMES]] (default table_cloth/, 61 frames).

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
  const auto out = examples::output_directory(argc, argv, "table_cloth");
  const int frames = examples::count_argument(argc, argv, 61, "the number of frames");

  // A 16 by 16 cloth (grid units) one unit above an 8 by 8 table top at z = 0.
  const Grid grid(17, 17, 1.0);
  TerzopoulosMaterial cloth_material;
  cloth_material.damping_density = 0.01;
  cloth_material.eta << 0.001, 0.0006, 0.0006, 0.001;
  TerzopoulosSurface cloth(grid, flat_grid_positions(grid, Eigen::Vector3d(-8, -8, 1)),
                           cloth_material);
  const BoxObstacle top{Eigen::Vector3d(-4, -4, -6), Eigen::Vector3d(4, 4, 0)};
  const std::vector<Obstacle> table{top};
  ContactSettings contact;
  contact.friction = 0.5;

  // The table as a mesh: a 2 by 2 grid on each of its 5 visible faces would do; its top suffices.
  const Grid top_grid(2, 2, 8.0);
  const TriangleMesh table_mesh = grid_triangle_mesh(
      top_grid, flat_grid_positions(top_grid, Eigen::Vector3d(-4, -4, 0)), "table");

  System system(cloth);
  system.add_force(0, gravity(Eigen::Vector3d(0, 0, -1e-4)));
  SemiImplicitStepper stepper;
  const std::vector<Eigen::Vector2d> points = grid.node_parameters();
  double deepest = 0.0;
  for (int frame = 0; frame < frames; ++frame) {
    const NodePositions r = cloth.positions(system.coordinates(0));
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_meshes({grid_triangle_mesh(grid, r, "cloth"), table_mesh}, out / name);
    for (int s = 0; s < 10; ++s) {
      stepper.step(system, 1.0);
      deepest = std::max(deepest, project_contacts(system, 0, table, points, contact));
    }
  }
  std::printf(
      "table cloth: deepest penetration before projection %.3e, after %.3e; corner at "
      "z = %.3f; frames in %s\n",
      deepest, max_penetration(system, 0, table, points), system.coordinates(0)[2],
      out.string().c_str());
  return 0;
}
