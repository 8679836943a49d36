// A multibody assembly of superquadrics (Terzopoulos 2003, eqs. 1.28-1.40): an arm hangs from a
// pivot by a ball joint, a spinning wheel turns on a hinge across it, a bob hangs from its end by a
// ball joint. Released 40 degrees off the vertical under gravity, undamped: the joints hold
// (Baumgarte plus projection) and the total energy is conserved.
// Usage: example_102_superquadric_assembly [OUTPUT_DIRECTORY [FRAMES]] (default 60 frames).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/superquadric/deformable_superquadric_model.h"
#include "dnurbs/io/mesh_export.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "superquadric_assembly");
  const int frames = examples::count_argument(argc, argv, 60, "the number of frames");
  const double pi = std::numbers::pi;

  // 1. Parts: q_s = (a, a1, a2, a3, e1, e2, 0...); (u, v) = (latitude, longitude), the poles at
  //    u = +-pi/2 are the body points (0, 0, +-a a3). Each part is rigid (6 velocities), under
  //    gravity: m g on its centre (its centre of mass), i.e. on its z velocity.
  const Eigen::Vector3d g(0, 0, -9.81);
  System system;
  std::vector<double> masses;
  const auto add_part = [&](double a1, double a2, double a3, double e1,
                            const Eigen::Vector3d& centre, const Eigen::Quaterniond& orientation) {
    SuperquadricShapeParameters q = SuperquadricShapeParameters::Zero();
    q.head<6>() << 1.0, a1, a2, a3, e1, 1.0;
    const DeformableSuperquadricModel part(q, centre, orientation);
    masses.push_back(part.reference_mass_properties().mass);
    const int index = system.add_model(part);
    system.add_force(index,
                     coordinate_force({2}, [w = masses.back() * g.z()](double) { return w; }));
    return index;
  };
  const Eigen::Vector2d top(pi / 2, 0.0), bottom(-pi / 2, 0.0);
  const Eigen::Vector3d down(std::sin(pi * 40 / 180), 0.0, -std::cos(pi * 40 / 180));
  const auto tilt = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -down);
  const int arm = add_part(0.08, 0.08, 0.5, 1.0, 0.5 * down, tilt);
  // The wheel's axle runs through two arm points at latitude -0.6, longitudes +-pi/2 (along y):
  // a flat-capped wheel (e1 = 0.3) whose half thickness is half their distance, spinning at
  // 8 rad/s about its axle (its body z axis).
  const double latitude = -0.6;
  const int wheel = add_part(
      0.25, 0.25, 0.08 * std::cos(latitude), 0.3, (0.5 - 0.5 * std::sin(latitude)) * down,
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()));
  system.set_velocities(wheel, (Eigen::VectorXd(6) << 0, 0, 0, 0, 0, 8.0).finished());
  const int bob = add_part(0.15, 0.15, 0.15, 1.0, 1.15 * down, tilt);
  // 3. Joints: the arm's top on the pivot, the hinge, the bob's top on the arm's bottom.
  ConstraintSolver joints;
  joints.add(system,
             PointTargetConstraint(arm, top, TargetTrajectory::fixed(Eigen::Vector3d::Zero())));
  joints.add(system, HingeConstraint(arm, Eigen::Vector2d(latitude, pi / 2),
                                     Eigen::Vector2d(latitude, -pi / 2), wheel, top, bottom));
  joints.add(system, PointToPointConstraint(arm, bottom, bob, top));
  joints.set_projection(true, 1e-12);  // rotating joints are non-linear in q: project back

  // 4. Run: Newmark with Newton iterations (the rotating parts' matrices depend on q).
  Integrator integrator(IntegratorSettings{.newton_iterations = 4});
  const auto energy = [&] {  // kinetic plus sum m (-g . c)
    double e = system.kinetic_energy();
    for (int part = 0; part < system.model_count(); ++part) {
      e -= masses[static_cast<size_t>(part)] * g.dot(system.coordinates(part).head<3>());
    }
    return e;
  };
  const double initial = energy();
  double violation = 0.0, drift = 0.0;
  const ModelTessellationSettings resolution{12, 24};  // latitudes, longitudes
  for (int frame = 0; frame < frames; ++frame) {
    std::vector<TriangleMesh> meshes;
    for (const auto& [part, name] : {std::pair{arm, "arm"}, {wheel, "wheel"}, {bob, "bob"}}) {
      meshes.push_back(
          tessellate_model(system.model(part), system.coordinates(part), resolution, name));
    }
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.obj", frame);
    export_meshes(meshes, out / name);
    for (int s = 0; s < 8; ++s) {
      joints.step(integrator, system, 2.5e-3);
      violation = std::max(violation, joints.max_violation(system));
      drift = std::max(drift, std::abs(energy() - initial) / std::abs(initial));
    }
  }
  std::printf(
      "superquadric assembly: t = %.2f, max joint violation %.1e, relative energy drift "
      "%.1e; frames in %s\n",
      system.time(), violation, drift, out.string().c_str());
  return 0;
}
