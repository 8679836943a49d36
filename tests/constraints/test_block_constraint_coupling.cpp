// A point-to-point constraint couples a constant D-NURBS sheet and a state-dependent deformable
// superquadric that the integrator factors block by block: the constraint solver's Schur
// complement goes through the per-block solve hook, the joint holds, the sheet's block is still
// factored once and the sheet carries the superquadric's weight through the joint alone.

#include <iostream>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "constraints/constraint_solver.h"
#include "constraints/point_constraints.h"
#include "dynamics/superquadric/deformable_superquadric_model.h"
#include "dynamics/dnurbs/dnurbs_surface.h"
#include "dynamics/core/forces.h"
#include "dynamics/integrators/integrator.h"
#include "dynamics/core/system.h"
#include "nurbs/knot_vector.h"

namespace dnurbs {
namespace {

// A flat bicubic 6 x 6 patch over [0, 1]^2 at z = 0.
NurbsSurface flat_sheet() {
  const KnotVector knots = KnotVector::clamped_uniform(3, 6);
  Eigen::MatrixX3d points(36, 3);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      points.row(i * 6 + j) << i / 5.0, j / 5.0, 0.0;
    }
  }
  return NurbsSurface(knots, knots, points);
}

TEST(BlockConstraintCoupling, SuperquadricHangsFromAClampedSheetByABallJoint) {
  DNurbsSurfaceMaterial material;
  material.damping_density = 0.5;
  material.a10 = 2.0;
  material.a01 = 2.0;
  DNurbsSurface sheet(flat_sheet(), material);
  sheet.fix_border();
  // An ellipsoid (global deformations free) whose north pole sits at the sheet's centre.
  SuperquadricShapeParameters shape = SuperquadricShapeParameters::Zero();
  shape << 1.0, 0.15, 0.15, 0.25, 1.0, 1.0, 0, 0, 0, 0, 0, 0, 0, 0;
  DeformableSuperquadricSettings settings;
  settings.parts = DeformableSuperquadricParts::global();
  settings.mass_density = 0.5;
  const Eigen::Vector2d pole(1.5707963267948966, 0.0);
  const Eigen::Vector2d middle(0.5, 0.5);
  const Eigen::Vector3d anchor = sheet.position(sheet.initial_coordinates(), middle);
  const DeformableSuperquadricModel probe(shape, Eigen::Vector3d::Zero(),
                                          Eigen::Quaterniond::Identity(), settings);
  const Eigen::Vector3d centre = anchor - probe.position(probe.initial_coordinates(), pole);
  const DeformableSuperquadricModel body(shape, centre, Eigen::Quaterniond::Identity(), settings);

  System system;
  system.add_model(sheet);
  system.add_model(body);
  system.add_force(1, gravity(Eigen::Vector3d(0.0, 0.0, -9.81)));  // the sheet has no load
  ConstraintSolver solver;
  solver.add(system, PointToPointConstraint(0, middle, 1, pole));
  ASSERT_LT(solver.max_violation(system), 1e-14);
  IntegratorSettings integrator_settings;  // newmark
  integrator_settings.newton_iterations = 2;
  Integrator integrator(integrator_settings);
  double largest_violation = 0.0;
  const int steps = 100;
  for (int k = 0; k < steps; ++k) {
    solver.step(integrator, system, 0.005);
    largest_violation = std::max(largest_violation, solver.max_violation(system));
  }
  const double sag = system.position(0, middle).z();
  std::cout << "superquadric on a sheet, 0.5 s: largest joint violation " << largest_violation
            << ", sheet centre at z = " << sag << "\n";
  // Baumgarte-stabilised acceleration-level rows with Newton iterations at the end-of-step
  // state: what is left is the unconverged non-linear part (the pole moves with the rotation and
  // shape) and round-off; 6e-16 measured.
  EXPECT_LT(largest_violation, 1e-8);
  // Only the joint pulls the sheet down (it has no load of its own).
  EXPECT_LT(sag, -1e-2);
  EXPECT_EQ(integrator.block_factorization_count(0), 1);
  EXPECT_GE(integrator.block_factorization_count(1), steps);
  EXPECT_TRUE(system.coordinates().allFinite());
}

}  // namespace
}  // namespace dnurbs
