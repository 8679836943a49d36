// Tests of dynamics/core/system.h: stacking of models (block-diagonal matrices, stacked
// coordinates) and value semantics.

#include "dnurbs/dynamics/core/system.h"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

DNurbsCurve string_model() {
  DNurbsCurveMaterial material;
  material.tension = 1.0;
  material.damping_density = 0.1;
  DNurbsCurve model(test::straight_curve(2, 6), material);
  model.fix_control_point(0);
  model.fix_control_point(7);
  return model;
}

DNurbsSurface plate_model() {
  DNurbsSurfaceMaterial material;
  material.a10 = 1.0;
  material.a01 = 1.0;
  material.b20 = 0.01;
  DNurbsSurface model(test::flat_patch(2, 2, 3, 3), material);
  model.fix_border();
  return model;
}

TEST(SystemStacking, OffsetsAndBlockDiagonalMatrices) {
  const DNurbsCurve curve = string_model();
  const DNurbsSurface surface = plate_model();
  System system;
  EXPECT_EQ(system.add_model(curve), 0);
  EXPECT_EQ(system.add_model(surface), 1);
  EXPECT_EQ(system.velocity_offset(1), curve.velocity_count());
  EXPECT_EQ(system.coordinate_count(), curve.coordinate_count() + surface.coordinate_count());
  EXPECT_EQ(system.coordinates(1), surface.initial_coordinates());
  const Eigen::MatrixXd M(system.constant_matrices()->mass);
  const int n = curve.velocity_count();
  EXPECT_EQ(M.topLeftCorner(n, n), Eigen::MatrixXd(curve.constant_matrices()->mass));
  EXPECT_EQ(M.bottomRightCorner(M.rows() - n, M.cols() - n),
            Eigen::MatrixXd(surface.constant_matrices()->mass));
  EXPECT_EQ(M.topRightCorner(n, M.cols() - n).norm(), 0.0);
  EXPECT_EQ(system.kronecker_block_size(), 3);
  // Fixed coordinates shifted by the model offsets.
  EXPECT_EQ(system.fixed_coordinates().front(), 0);
  EXPECT_EQ(system.fixed_coordinates()[6], n + surface.fixed_coordinates().front());
  EXPECT_THROW(system.model(2), Error);
}

TEST(SystemStacking, SteppingTogetherEqualsSteppingEachAlone) {
  const DNurbsCurve curve = string_model();
  const DNurbsSurface surface = plate_model();
  const Force push = point_force(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(0.0, 0.3, 1.0));
  System both;
  both.add_model(curve);
  both.add_model(surface);
  both.add_force(0, push);
  both.add_force(1, push);
  System alone_curve(curve);
  alone_curve.add_force(0, push);
  System alone_surface(surface);
  alone_surface.add_force(0, push);
  Integrator a;
  Integrator b;
  Integrator c;
  for (int k = 0; k < 30; ++k) {
    a.step(both, 0.02);
    b.step(alone_curve, 0.02);
    c.step(alone_surface, 0.02);
  }
  // Block-diagonal systems decouple; the factorizations differ in ordering: round-off only.
  EXPECT_LT((both.coordinates(0) - alone_curve.coordinates()).lpNorm<Eigen::Infinity>(), 1e-13);
  EXPECT_LT((both.coordinates(1) - alone_surface.coordinates()).lpNorm<Eigen::Infinity>(), 1e-13);
}

TEST(SystemValue, CopiesAreIndependent) {
  System original(string_model());
  original.add_force(0, point_force(Eigen::Vector2d(0.3, 0.0), Eigen::Vector3d(0, 1, 0)));
  System copy = original;
  Integrator integrator;
  integrator.step(copy, 0.01);
  EXPECT_EQ(original.time(), 0.0);
  EXPECT_EQ(original.coordinates(), original.model(0).initial_coordinates());
  EXPECT_NE(copy.coordinates(), original.coordinates());
  EXPECT_NE(&copy.model(0), &original.model(0));
}

// A System holds copies of its models: a point fixed on the model after adding it does not reach
// the System (issue 21's friction), which fix_point / fix_border do, before or during a run.
TEST(SystemBoundary, FixingThroughTheSystemActsOnItsCopy) {
  DNurbsSurfaceMaterial material;
  material.a10 = material.a01 = 1.0;
  const DNurbsSurface free_sheet(test::flat_patch(2, 2, 3, 3), material);
  DNurbsSurface fixed_first = free_sheet;
  fixed_first.fix_border();
  System before(fixed_first);
  System through(free_sheet);
  through.fix_border(0);
  DNurbsSurface model = free_sheet;
  System ignored(model);
  model.fix_border();  // the System's copy is not touched
  for (System* system : {&before, &through, &ignored}) {
    system->add_force(0, gravity(Eigen::Vector3d(0, 0, -1)));
  }
  // One integrator per system: an integrator keeps the factorization of the system it steps
  Integrator integrator;
  Integrator integrator_through;
  Integrator integrator_ignored;
  for (int n = 0; n < 10; ++n) {
    integrator.step(before, 0.01);
    integrator_through.step(through, 0.01);
    integrator_ignored.step(ignored, 0.01);
  }
  EXPECT_EQ(through.coordinates(), before.coordinates());
  EXPECT_EQ(through.fixed_coordinates(), before.fixed_coordinates());
  EXPECT_TRUE(ignored.fixed_coordinates().empty());
  EXPECT_LT(ignored.coordinates()[2], -1e-4);  // its corner fell

  // Fixed mid-run: the point stays where it was, its velocity zero; the rest keeps moving
  const int centre = 12;  // control point (2, 2) of the 5 x 5 net
  const Eigen::Vector3d held = before.coordinates().segment<3>(3 * centre);
  ASSERT_LT(held.z(), -1e-4);
  before.fix_point(0, centre);
  EXPECT_EQ(before.velocities().segment<3>(3 * centre), Eigen::Vector3d::Zero());
  const Eigen::VectorXd q = before.coordinates();
  for (int n = 0; n < 10; ++n) {
    integrator.step(before, 0.01);
  }
  EXPECT_EQ(before.coordinates().segment<3>(3 * centre), held);
  EXPECT_GT((before.coordinates() - q).norm(), 1e-6);
  EXPECT_THROW(before.fix_point(1, 0), Error);
  EXPECT_THROW(before.fix_point(0, 25), Error);
}

// One integrator stepping two systems in turn (a clamped and a free sheet, built alike, so that
// their layouts were once counted the same) steps each as its own integrator would: a System's
// revision is unique, so the integrator never reuses the other's factorization.
TEST(SystemBoundary, AnIntegratorSteppingTwoSystemsKeepsThemApart) {
  DNurbsSurfaceMaterial material;
  material.a10 = material.a01 = 1.0;
  DNurbsSurface clamped(test::flat_patch(2, 2, 3, 3), material);
  clamped.fix_border();
  const DNurbsSurface free_sheet(test::flat_patch(2, 2, 3, 3), material);
  System a(clamped);
  System b(free_sheet);
  System a_alone(clamped);
  System b_alone(free_sheet);
  for (System* system : {&a, &b, &a_alone, &b_alone}) {
    system->add_force(0, gravity(Eigen::Vector3d(0, 0, -1)));
  }
  EXPECT_NE(a.revision(), b.revision());
  Integrator shared;
  Integrator own_a;
  Integrator own_b;
  for (int n = 0; n < 10; ++n) {
    shared.step(a, 0.01);
    shared.step(b, 0.01);
    own_a.step(a_alone, 0.01);
    own_b.step(b_alone, 0.01);
  }
  EXPECT_EQ(a.coordinates(), a_alone.coordinates());
  EXPECT_EQ(b.coordinates(), b_alone.coordinates());
}

TEST(SystemState, SettersRejectBadSizesAndNonFiniteValues) {
  System system(string_model());
  EXPECT_THROW(system.set_coordinates(0, Eigen::VectorXd::Zero(3)), Error);
  Eigen::VectorXd q = system.coordinates();
  q[4] = std::nan("");
  EXPECT_THROW(system.set_coordinates(0, q), Error);
  EXPECT_THROW(system.set_time(std::nan("")), Error);
  // Velocities of fixed coordinates are zeroed.
  system.set_velocities(0, Eigen::VectorXd::Ones(system.velocity_count()));
  EXPECT_EQ(system.velocities()[0], 0.0);
  EXPECT_EQ(system.velocities()[3], 1.0);
}

}  // namespace
}  // namespace dnurbs
