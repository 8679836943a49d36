// Sculpting a D-NURBS surface into a hat (Terzopoulos 2003, eqs. 1.24-1.27): a flat bicubic sheet
// with a clamped border is shaped by forces and springs on its control points and on points of the
// surface, each with its own time schedule, stepped by Newmark; every frame is written as OBJ.
// Usage: example_101_sculpting [OUTPUT_DIRECTORY [FRAMES]] (default sculpting/, 60 frames).

#include <algorithm>
#include <cstdio>

#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/nurbs/knot_vector.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "sculpting");
  const int frames = examples::count_argument(argc, argv, 60, "the number of frames");

  // 1. The clay: a flat bicubic sheet of 9 x 9 control points over [-1.2, 1.2]^2 (control point
  //    (i, j) is node 9 i + j), with tension (a10, a01) and rigidity (b20, b11, b02).
  const int n = 9;
  Eigen::MatrixX3d points(n * n, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      points.row(n * i + j) << -1.2 + 0.3 * i, -1.2 + 0.3 * j, 0.0;
    }
  }
  const KnotVector knots = KnotVector::clamped_uniform(3, n);
  DNurbsSurfaceMaterial clay;
  clay.damping_density = 4.0;
  clay.a10 = clay.a01 = 0.1;
  clay.b20 = clay.b11 = clay.b02 = 0.02;
  DNurbsSurface sheet(NurbsSurface(knots, knots, points), clay);
  sheet.fix_border();  // the border control points are eliminated from every solve
  System system(sheet);

  // 2. The crown: a force on the central control point, ramped up over the first second.
  system.add_force(0, control_point_force({n * 4 + 4}, [](double t) {
                     return Eigen::Vector3d(0, 0, 6.0 * std::min(t, 1.0));
                   }));
  // 3. Its shoulders: from t = 0.5, springs k (target - P) from four control points to 0.6 above
  //    them (fixed weights: velocity and coordinate indices coincide). State-dependent forces
  //    are explicit in the integrators: at this dt, k = 20 on one control point diverges.
  for (const int i : {3, 5}) {
    for (const int j : {3, 5}) {
      const int node = n * i + j;
      const Eigen::Vector3d target = points.row(node).transpose() + Eigen::Vector3d(0, 0, 0.6);
      system.add_force(0, [node, target](const Model& model, double t, ConstVectorRef q,
                                         ConstVectorRef, VectorRef force) {
        const int offset = model.control_point_offset(node);
        force.segment<3>(offset) += (t < 0.5 ? 0.0 : 4.0) * (target - q.segment<3>(offset));
      });
    }
  }
  // 4. The brim: "mouse springs" (k = 30) hold four surface points (u, v) at their targets,
  //    which sink by 0.2 between t = 1 and t = 2. System springs are implicit: their stiffness
  //    is in the step matrix (dynamics/core/spring.h), so any k is stable.
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(0.15, 0.5), Eigen::Vector2d(0.85, 0.5),
                                   Eigen::Vector2d(0.5, 0.15), Eigen::Vector2d(0.5, 0.85)}) {
    const Eigen::Vector3d start = system.position(0, u);
    const auto target = [start](double t) {
      return Eigen::Vector3d(start - Eigen::Vector3d(0, 0, 0.2 * std::clamp(t - 1.0, 0.0, 1.0)));
    };
    system.add_spring(0, mouse_spring(u, target, 30.0));
  }
  // 5. Flattening the crown: from t = 1.5, a force presses on the surface point (0.5, 0.5).
  system.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), [](double t) {
                     return Eigen::Vector3d(0, 0, t < 1.5 ? 0.0 : -4.0);
                   }));

  // 6. Run: Newmark with constant matrices (factored once), 5 steps of 0.01 per frame.
  Integrator integrator(IntegratorSettings{IntegratorScheme::kNewmark});
  const ModelTessellationSettings resolution{24, 24};  // cells along u and v
  for (int frame = 0; frame < frames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_mesh(tessellate_model(system.model(0), system.coordinates(0), resolution, "hat"),
                out / name);
    for (int s = 0; s < 5; ++s) {
      integrator.step(system, 0.01);
    }
  }
  const Eigen::MatrixX3d moved = sheet.control_points(system.coordinates(0)) - points;
  double border = 0.0;
  for (int k = 0; k < n; ++k) {
    for (const int node : {k, n * (n - 1) + k, n * k, n * k + n - 1}) {
      border = std::max(border, moved.row(node).norm());
    }
  }
  std::printf(
      "sculpting: t = %.2f, crown z = %.3f, shoulder z = %.3f, border moved %.1e; "
      "frames in %s\n",
      system.time(), system.position(0, {0.5, 0.5}).z(), system.position(0, {0.4, 0.4}).z(), border,
      out.string().c_str());
  return 0;
}
