#include "needs.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/dnurbs/local_sculpting.h"
#include "dnurbs/dynamics/integrators/static_equilibrium.h"
#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/nurbs/swung_refinement.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "step_timing.h"

namespace dnurbs::bench {

namespace {

std::string constant_matrices(const System& system) {
  return system.matrices_are_constant() ? "M D K" : "none";
}

int active_coordinates(const System& system) {
  return system.velocity_count() - static_cast<int>(system.fixed_coordinates().size());
}

}  // namespace

void run_needs(const BenchOptions& options, BoundChecks& checks) {
  const double minimum_seconds = options.quick ? 0.02 : 0.3;
  CsvFile csv(
      options.out_dir / "needs.csv",
      {"model", "active_coordinates", "total_coordinates", "constant_matrices",
       "naive_seconds_per_step", "chosen_seconds_per_step", "saving_ratio", "error_against_naive"});
  // error: the chosen path's static-shape error relative to the naive one's displacement, where
  // both model the same thing ("-": a different model, as fixed against free weights)
  auto report = [&](const std::string& name, const System& chosen, const System& naive,
                    double naive_step, double chosen_step, const std::string& error = "-") {
    csv.row({name, std::to_string(active_coordinates(chosen)),
             std::to_string(active_coordinates(naive)), constant_matrices(chosen),
             number(naive_step), number(chosen_step), number(naive_step / chosen_step), error});
    std::cerr << "needs: " << name << ' ' << active_coordinates(chosen) << " of "
              << active_coordinates(naive) << " coordinates, saving " << naive_step / chosen_step
              << '\n';
    // The chosen path solves a subset of the naive path's coordinates with the same scheme.
    checks.expect(active_coordinates(chosen) <= active_coordinates(naive),
                  name + ": chosen path has more active coordinates than the naive one");
  };

  // Fixed against free weights, same membrane. Free weights are light coordinates: dt = 1e-5
  // (their light weight modes), a blown-up step restarts (counted).
  {
    const int side = options.quick ? 6 : 12;
    System fixed(clamped_membrane(side, WeightMode::kFixed, 0.1));
    System free(clamped_membrane(side, WeightMode::kFree, 0.1));
    for (System* system : {&fixed, &free}) {
      system->add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, 1e-3)));
    }
    int restarts = 0;
    const double naive =
        seconds_per_step(free, IntegratorSettings{}, 1e-5, minimum_seconds, &restarts);
    const double chosen = seconds_per_step(fixed, IntegratorSettings{}, 1e-5, minimum_seconds);
    if (restarts > 0) {
      std::cerr << "needs: free-weight membrane restarted " << restarts << " times\n";
    }
    report("dnurbs_surface_fixed_weights", fixed, free, naive, chosen);
  }
  // Rigid superquadric as a 6-coordinate body against the full deformable model.
  {
    const System rigid = spinning_superquadric(DeformableSuperquadricParts::rigid());
    const System full = spinning_superquadric(DeformableSuperquadricParts::full());
    const double naive = seconds_per_step(full, IntegratorSettings{}, 1e-2, minimum_seconds);
    const double chosen = seconds_per_step(rigid, IntegratorSettings{}, 1e-2, minimum_seconds);
    report("superquadric_rigid_parts", rigid, full, naive, chosen);
  }
  // A mixed scene (constant fixed-weight membrane + state-dependent superquadric): the
  // integrator factors per model block, so the membrane's block is factored once and only the
  // superquadric's is re-factored each step. The old whole-system re-factorization is no longer
  // available to time, so "naive" is the sum of the two models stepped in separate Systems (what
  // the scene should cost) and "chosen" the mixed System's step: a saving_ratio near 1 means the
  // scene pays only for its own degrees of freedom, below 1 is the overhead of mixing.
  {
    const int side = options.quick ? 6 : 12;
    System membrane(clamped_membrane(side, WeightMode::kFixed, 0.1));
    membrane.add_force(0, point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0, 0, 1e-3)));
    const System body = spinning_superquadric(DeformableSuperquadricParts::global());
    System mixed = membrane;
    mixed.add_model(body.model(0));
    mixed.set_velocities(1, body.velocities(0));
    const double separate =
        seconds_per_step(membrane, IntegratorSettings{}, 1e-2, minimum_seconds) +
        seconds_per_step(body, IntegratorSettings{}, 1e-2, minimum_seconds);
    const double together = seconds_per_step(mixed, IntegratorSettings{}, 1e-2, minimum_seconds);
    report("mixed_scene_block_factorization", mixed, mixed, separate, together);
  }
  // A swung surface against the tensor-product D-NURBS surface of the same shape and resolution
  // (Qin & Terzopoulos, Dynamic NURBS swung surfaces, CAD 27(2) 1995): the exact sphere, both
  // curves refined by k knots per span, pulled by a spring, same material, Newmark with one
  // Newton iteration for both. The swung model has 2 (m + n) coordinates against 3 m n, but
  // re-assembles its dense profile-trajectory coupling and re-factors it every step; the twin
  // (fixed weights) factors its constant scalar matrix once and back-substitutes. They model
  // different motions (the twin may dent locally), so no error against the twin is given.
  for (const int knots : options.quick ? std::vector<int>{0} : std::vector<int>{0, 3, 7, 15}) {
    const SwungSurface sphere = refine_swung_surface(swung_sphere(1.0), knots, knots);
    DNurbsSurfaceMaterial material;
    material.damping_density = 1.0;
    material.a10 = material.a01 = 0.05;
    material.b20 = material.b02 = 0.005;
    DNurbsSwungSurface swung(sphere, material);
    swung.fix_poles();
    System chosen(swung);
    System naive(DNurbsSurface(sphere.to_nurbs_surface(), material));
    const Eigen::Vector2d at(0.3, 0.1);
    const Eigen::Vector3d target = 1.2 * sphere.point(at.x(), at.y());
    for (System* system : {&chosen, &naive}) {
      system->add_force(0, spring_force(
                               at, [target](double) { return target; }, 5.0));
    }
    IntegratorSettings settings;
    settings.newton_iterations = 1;
    int restarts = 0;
    const double naive_step = seconds_per_step(naive, settings, 1e-2, minimum_seconds, &restarts);
    const double chosen_step = seconds_per_step(chosen, settings, 1e-2, minimum_seconds, &restarts);
    if (restarts > 0) {
      std::cerr << "needs: swung sphere (" << knots << " knots per span) restarted " << restarts
                << " times\n";
    }
    report("swung_sphere_" + std::to_string(sphere.profile().control_point_count()) + "x" +
               std::to_string(sphere.trajectory().control_point_count()) +
               "_against_tensor_product",
           chosen, naive, naive_step, chosen_step);
  }
  // PDE surface: deformation region against the whole grid.
  {
    const int nodes = options.quick ? 33 : 65;
    const System region = pushed_pde_surface(nodes, true);
    const System whole = pushed_pde_surface(nodes, false);
    const IntegratorSettings settings{IntegratorScheme::kImplicitEuler};
    const double naive = seconds_per_step(whole, settings, 1.0 / 240.0, minimum_seconds);
    const double chosen = seconds_per_step(region, settings, 1.0 / 240.0, minimum_seconds);
    report("pde_surface_deformation_region", region, whole, naive, chosen);
  }
  // Local sculpting: a point force on a large clamped sheet with the control points outside its
  // span (grown by a margin of rings) frozen, against the whole sheet; the error is that of the
  // static shape K q = f on a 41 x 41 grid of surface points.
  {
    const int side = options.quick ? 20 : 60;
    const Eigen::Vector2d at(0.3, 0.4);
    auto sheet = [&](int margin) {
      DNurbsSurface model = clamped_membrane(side, WeightMode::kFixed, 0.1);
      if (margin >= 0) {
        freeze_outside_sculpted_region(model, {{at}, {}}, margin);
      }
      System system(model);
      system.add_force(0, point_force(at, Eigen::Vector3d(0, 0, 1e-3)));
      return system;
    };
    System whole = sheet(-1);
    const IntegratorSettings settings{IntegratorScheme::kImplicitEuler};
    const double naive = seconds_per_step(whole, settings, 1.0 / 60.0, minimum_seconds);
    solve_static_equilibrium(whole);
    for (const int margin : {2, 8}) {
      System local = sheet(margin);
      const double chosen = seconds_per_step(local, settings, 1.0 / 60.0, minimum_seconds);
      solve_static_equilibrium(local);
      double error = 0.0;
      double largest = 0.0;
      for (int a = 0; a <= 40; ++a) {
        for (int b = 0; b <= 40; ++b) {
          const Eigen::Vector2d uv(a / 40.0, b / 40.0);
          const Eigen::Vector3d reference = whole.position(0, uv);
          error = std::max(error, (local.position(0, uv) - reference).norm());
          largest = std::max(largest, std::abs(reference.z()));
        }
      }
      report("dnurbs_surface_local_sculpting_margin_" + std::to_string(margin), local, whole, naive,
             chosen, number(error / largest));
      checks.expect(error < largest,
                    "local sculpting: frozen solve further off than the "
                    "displacement itself");
    }
  }
}

}  // namespace dnurbs::bench
