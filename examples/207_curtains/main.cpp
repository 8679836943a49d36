// Opening a woollen and a silk curtain (Wu & de Melo, figures 10 and 11): eta_ii = 1e-3, eta_12 =
// 1e-6 and xi = 2e-6 (wool) or 0 (silk), hanging from a rail under gravity; the same force
// along the upper line draws each curtain toward its fixed first node. The upper nodes (the
// hooks) slide on the rail and swing across it (their z is fixed). Writes frame_NNN.obj (both
// curtains) into argv[1].
// Usage: example_207_curtains [OUTPUT_DIRECTORY [FRAMES]] (default curtains/, 61 frames).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/line_force.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/terzopoulos_surface.h"
#include "dnurbs/dynamics/integrators/semi_implicit_step.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/surface/grid.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "curtains");
  const int frames = examples::count_argument(argc, argv, 61, "the number of frames");

  // 16 by 12 grid units, u along x on the rail, v downwards; pleated (y ripple of period 4).
  const Grid grid(17, 13, 1.0);
  System system;
  for (const double xi : {2e-6, 0.0}) {
    const double offset = xi > 0.0 ? 0.0 : 6.0;  // silk behind wool
    NodePositions rest(grid.node_count(), 3);
    for (int k = 0; k < grid.node_count(); ++k) {
      const auto [i, j] = grid.node(k);
      rest.row(k) << i, offset + 0.4 * std::sin(std::numbers::pi * i / 2.0), -j;
    }
    TerzopoulosMaterial cloth;
    cloth.damping_density = 0.002;
    cloth.eta << 1e-3, 1e-6, 1e-6, 1e-3;
    cloth.xi << xi, xi, xi, xi;
    TerzopoulosSettings settings;
    settings.normal = NormalApproximation::kChristoffel;
    TerzopoulosSurface curtain(grid, rest, cloth, settings);
    curtain.fix_point(0);
    for (int i = 1; i < grid.nu(); ++i) {  // the rail: the upper line keeps its height
      curtain.fix_coordinate(3 * grid.index(i, 0) + 2);
    }
    const int m = system.add_model(curtain);
    system.add_force(m, gravity(Eigen::Vector3d(0, 0, -1e-4)));
    std::vector<Eigen::Vector2d> upper_line = grid.row_parameters(0);
    upper_line.erase(upper_line.begin());  // the first hook is fixed
    system.add_force(m, line_force(upper_line, [](double t) {
                       return Eigen::Vector3d(t < 450.0 ? -5e-4 : 0.0, 0, 0);  // pull, let go
                     }));
  }
  SemiImplicitStepper stepper;
  for (int frame = 0; frame < frames; ++frame) {
    std::vector<TriangleMesh> meshes;
    for (int m = 0; m < 2; ++m) {
      const auto& curtain = dynamic_cast<const TerzopoulosSurface&>(system.model(m));
      meshes.push_back(grid_triangle_mesh(grid, curtain.positions(system.coordinates(m)),
                                          m == 0 ? "wool" : "silk"));
    }
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_meshes(meshes, out / name);
    for (int s = 0; s < 10; ++s) {
      stepper.step(system, 1.0);
    }
  }
  const int last = 3 * grid.index(grid.nu() - 1, 0);
  std::printf("curtains: free end of the rail at x = %.2f (wool), %.2f (silk); frames in %s\n",
              system.coordinates(0)[last], system.coordinates(1)[last], out.string().c_str());
  return 0;
}
