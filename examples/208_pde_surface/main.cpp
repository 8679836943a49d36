// The dynamic PDE surface (Romero 2005, eq. 8) with two pulsing forces, each simulating only its
// deformation region (the rest of the grid is fixed and costs nothing), sub-stepped to 24 frames
// per second. Writes frame_NNN.obj into argv[1].
// Usage: example_208_pde_surface [OUTPUT_DIRECTORY [FRAMES]] (default pde_surface/, 49 frames).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/pde_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/surface/grid.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "pde_surface");
  const int frames = examples::count_argument(argc, argv, 49, "the number of frames");

  const Grid grid(41, 41, 1.0 / 40);  // a unit square
  PdeSurfaceMaterial material;        // b = d = 1, c = 2: the biharmonic
  material.damping_density = 10.0;
  const std::vector<Eigen::Vector3d> centres{{0.3, 0.3, 0.0}, {0.7, 0.6, 0.0}};
  const PdeSurface surface(grid, flat_grid_positions(grid, Eigen::Vector3d::Zero()), material,
                           {{centres[0], 0.25}, {centres[1], 0.2}});
  std::printf("PDE surface: %d of %d nodes simulated\n", surface.coordinate_count() / 3,
              grid.node_count());
  System system(surface);
  for (int f = 0; f < 2; ++f) {
    const std::vector<int> nodes = surface.nodes_within(centres[static_cast<size_t>(f)], 0.06);
    const double scale = 1.0 / static_cast<double>(nodes.size());
    system.add_force(0, control_point_force(nodes, [f, scale](double t) {
                       const double pulse = std::sin(std::numbers::pi * t * (f + 1));
                       return Eigen::Vector3d(0, 0, 100.0 * scale * pulse);
                     }));
  }
  Integrator integrator(IntegratorSettings{IntegratorScheme::kNewmark});
  for (int frame = 0; frame < frames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_mesh(grid_triangle_mesh(grid, surface.positions(system.coordinates(0)), "pde"),
                out / name);
    advance_frame(integrator, system, 1.0 / 240.0);  // 10 sub-steps per frame at 24 fps
  }
  std::printf("PDE surface: %d factorization(s) for %.1f s; frames in %s\n",
              integrator.factorization_count(), system.time(), out.string().c_str());
  return 0;
}
