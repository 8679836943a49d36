// Tests of dynamics/swung/dnurbs_swung_surface_shape.cpp: the swung model's shape through the
// Model contract (parameter domain with poles and seams, outward orientation, exact normals,
// the tensor-product twin as its exact shape, tessellation) and its tangent kinematics against
// finite differences and inside a surface normal constraint.

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <variant>

#include <gtest/gtest.h>

#include "dnurbs/constraints/constraint_solver.h"
#include "dnurbs/constraints/surface_constraints.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/nurbs/swung_shapes.h"
#include "tests/dynamics/swung/swung_model_helpers.h"

namespace dnurbs {
namespace {

using testing::model_cases;
using testing::perturbed;
using testing::random_vector;
using testing::settings_for;

TEST(SwungShape, DomainHasThePolesAndSeamsOfThePrototypes) {
  const DNurbsSwungSurface sphere(swung_sphere(1.0));
  ParameterDomain domain = sphere.parameter_domain(sphere.initial_coordinates());
  EXPECT_TRUE(domain.pole_u_min && domain.pole_u_max && domain.periodic_v);
  EXPECT_FALSE(domain.periodic_u);
  EXPECT_EQ(domain.u_min, 0.0);
  EXPECT_EQ(domain.u_max, 1.0);
  const DNurbsSwungSurface torus(swung_torus(2.0, 0.5));
  domain = torus.parameter_domain(torus.initial_coordinates());
  EXPECT_TRUE(domain.periodic_u && domain.periodic_v);
  const DNurbsSwungSurface hat(swung_hat(1.5, 0.8, 1.0));
  domain = hat.parameter_domain(hat.initial_coordinates());
  EXPECT_TRUE(domain.pole_u_min && !domain.pole_u_max && domain.periodic_v);
  // A pole opened by moving the profile's end off the axis is no pole any more.
  Eigen::VectorXd q = sphere.initial_coordinates();
  q[sphere.profile_offset(0)] = 0.1;
  domain = sphere.parameter_domain(q);
  EXPECT_FALSE(domain.pole_u_min);
  EXPECT_TRUE(domain.pole_u_max);
}

TEST(SwungShape, NormalsPointOutwardAndAreExact) {
  // The sphere: u from south to north and v counter-clockwise make S_u x S_v point inward, so
  // the outward normal is S_v x S_u; its unit normal is x / |x| up to round-off, poles included.
  const DNurbsSwungSurface sphere(swung_sphere(1.3));
  EXPECT_EQ(sphere.normal_orientation(), NormalOrientation::kSvCrossSu);
  const ParametricSurface surface = sphere.parametric_surface(sphere.initial_coordinates());
  EXPECT_EQ(surface.orientation(), NormalOrientation::kSvCrossSu);
  EXPECT_TRUE(surface.has_normal_function());
  double worst = 0.0;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double u = i / 10.0;
      const double v = j / 16.0;
      const Eigen::Vector3d x = surface.point(u, v);
      worst = std::max(worst, (surface.unit_normal(u, v) - x.normalized()).norm());
    }
  }
  EXPECT_LT(worst, 1e-13);  // the exact sphere and its exact normal: round-off
  // The torus: outward from the tube's centre circle.
  const DNurbsSwungSurface torus(swung_torus(2.0, 0.5));
  const ParametricSurface ring = torus.parametric_surface(torus.initial_coordinates());
  for (const auto& [u, v] : {std::pair{0.1, 0.2}, std::pair{0.6, 0.9}, std::pair{0.35, 0.5}}) {
    const Eigen::Vector3d x = ring.point(u, v);
    const Eigen::Vector3d centre = 2.0 * Eigen::Vector3d(x.x(), x.y(), 0.0).normalized();
    EXPECT_LT((ring.unit_normal(u, v) - (x - centre).normalized()).norm(), 1e-13);
  }
  // Open surfaces: the hat (apex down to the brim) and a flat disk keep S_u x S_v, which points
  // away from the axis on the hat's side and up on the disk.
  EXPECT_EQ(DNurbsSwungSurface(swung_hat(1.5, 0.8, 1.0)).normal_orientation(),
            NormalOrientation::kSuCrossSv);
  const DNurbsSwungSurface disk(swung_open_profile(0.0, 0.0, 1.0, 0.0, 5));
  EXPECT_EQ(disk.normal_orientation(), NormalOrientation::kSuCrossSv);
  EXPECT_LT((disk.parametric_surface(disk.initial_coordinates()).unit_normal(0.4, 0.3) -
             Eigen::Vector3d::UnitZ())
                .norm(),
            1e-15);
}

TEST(SwungShape, ExactShapeIsTheTensorProductTwinAndTheMeshFollowsIt) {
  const DNurbsSwungSurface model(swung_sphere(1.0));
  const Eigen::VectorXd q = perturbed(model, 17);
  const std::optional<Shape> shape = model.exact_shape(q);
  ASSERT_TRUE(shape && std::holds_alternative<NurbsSurface>(*shape));
  const NurbsSurface& twin = std::get<NurbsSurface>(*shape);
  EXPECT_EQ(twin.control_point_count_u(), 5);
  EXPECT_EQ(twin.control_point_count_v(), 8);
  double worst = 0.0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) {
      const Eigen::Vector2d u(i / 8.0, j / 8.0);
      worst = std::max(worst, (twin.point(u.x(), u.y()) - model.position(q, u)).norm());
    }
  }
  EXPECT_LT(worst, 1e-14);  // the same rational functions in another order: round-off
  // The mesh: one vertex per pole, no seam duplicates, outward normals at every vertex.
  ModelTessellationSettings settings;
  settings.segments_u = 6;
  settings.segments_v = 8;
  const TriangleMesh mesh =
      tessellate_model(model, model.initial_coordinates(), settings, "sphere");
  EXPECT_EQ(mesh.vertex_count(), 5 * 8 + 2);
  EXPECT_EQ(mesh.triangle_count(), 2 * 8 * 4 + 2 * 8);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    const Eigen::Vector3d x = mesh.vertices.row(k).transpose();
    const Eigen::Vector3d n = mesh.normals.row(k).transpose();
    EXPECT_LT((n - x.normalized()).norm(), 1e-13) << k;
  }
}

// S_u, S_v, their Jacobians, J qd and Jdot qd against central differences.
TEST(SwungShape, TangentKinematicsMatchFiniteDifferences) {
  for (const testing::ModelCase& c : model_cases()) {
    const DNurbsSwungSurface model(c.surface, {}, settings_for(c.mode));
    const Eigen::VectorXd q = perturbed(model, 19);
    const Eigen::VectorXd qd = random_vector(q.size(), 23);
    const auto tangents_at = [&](const Eigen::VectorXd& at, const Eigen::Vector2d& u) {
      TangentKinematics t;
      model.tangent_kinematics(at, qd, u, t);
      return t;
    };
    // J_u, J_v as dense 3 by #coordinates matrices from the listed columns.
    const auto dense = [&](const TangentKinematics& t, bool along_v) {
      Eigen::MatrixXd j = Eigen::MatrixXd::Zero(3, q.size());
      for (size_t c2 = 0; c2 < t.columns.size(); ++c2) {
        j.col(t.columns[c2]) = (along_v ? t.jv : t.ju).col(static_cast<Eigen::Index>(c2));
      }
      return j;
    };
    // Off every knot (the random curves have knots at 0.2, 0.45, 0.7 and 0.15, 0.35, 0.5, ...),
    // where central differences of S lose an order.
    for (const Eigen::Vector2d& u : {Eigen::Vector2d(0.13, 0.42), Eigen::Vector2d(0.62, 0.93)}) {
      const TangentKinematics t = tangents_at(q, u);
      EXPECT_TRUE(std::is_sorted(t.columns.begin(), t.columns.end()) &&
                  std::adjacent_find(t.columns.begin(), t.columns.end()) == t.columns.end())
          << c.name;
      const double h = 1e-6;
      const Eigen::Vector3d su = (model.position(q, u + Eigen::Vector2d(h, 0)) -
                                  model.position(q, u - Eigen::Vector2d(h, 0))) /
                                 (2 * h);
      const Eigen::Vector3d sv = (model.position(q, u + Eigen::Vector2d(0, h)) -
                                  model.position(q, u - Eigen::Vector2d(0, h))) /
                                 (2 * h);
      // O(h^2) truncation + O(1e-16 / h) round-off.
      EXPECT_LT((t.su - su).norm(), 1e-8 * (1.0 + su.norm())) << c.name;
      EXPECT_LT((t.sv - sv).norm(), 1e-8 * (1.0 + sv.norm())) << c.name;
      for (int k = 0; k < q.size(); ++k) {
        Eigen::VectorXd plus = q;
        Eigen::VectorXd minus = q;
        plus[k] += h;
        minus[k] -= h;
        const TangentKinematics a = tangents_at(plus, u);
        const TangentKinematics b = tangents_at(minus, u);
        EXPECT_LT((dense(t, false).col(k) - (a.su - b.su) / (2 * h)).norm(), 1e-8) << c.name;
        EXPECT_LT((dense(t, true).col(k) - (a.sv - b.sv) / (2 * h)).norm(), 1e-8) << c.name;
      }
      EXPECT_LT((t.su_rate - dense(t, false) * qd).norm(), 1e-13 * (1.0 + t.su_rate.norm()));
      EXPECT_LT((t.sv_rate - dense(t, true) * qd).norm(), 1e-13 * (1.0 + t.sv_rate.norm()));
      // Jdot qd = d/ds (J(q + s qd) qd): O(s^2) truncation + O(1e-16 / s) round-off.
      const double s = 1e-5;
      const TangentKinematics forward = tangents_at(q + s * qd, u);
      const TangentKinematics backward = tangents_at(q - s * qd, u);
      const Eigen::Vector3d su_bias =
          (dense(forward, false) * qd - dense(backward, false) * qd) / (2 * s);
      const Eigen::Vector3d sv_bias =
          (dense(forward, true) * qd - dense(backward, true) * qd) / (2 * s);
      EXPECT_LT((t.su_bias - su_bias).norm(), 1e-7 * (1.0 + su_bias.norm())) << c.name;
      EXPECT_LT((t.sv_bias - sv_bias).norm(), 1e-7 * (1.0 + sv_bias.norm())) << c.name;
      EXPECT_GT(t.su_bias.norm() + t.sv_bias.norm(), 1e-3) << c.name;  // bilinear: never zero
    }
  }
}

// A swung sphere pulled by a spring for 1 s with its normal held at one point (and, optionally,
// nothing else): the largest violation |e . (S_u x S_v)| of the Baumgarte-stabilized constraint
// relative to |S_u x S_v|, with `constrained` false the normal's own deviation.
double normal_violation(double dt, bool constrained, bool projection) {
  DNurbsSurfaceMaterial material;
  material.damping_density = 1.0;
  material.a10 = material.a01 = 0.05;
  material.b20 = material.b02 = 0.005;
  DNurbsSwungSurface sphere(swung_sphere(1.0), material);
  sphere.fix_poles();
  System system(sphere);
  const Eigen::Vector2d normal_at(0.6, 0.3);
  const Eigen::Vector3d normal =
      sphere.parametric_surface(sphere.initial_coordinates()).unit_normal(0.6, 0.3);
  const SurfaceNormalConstraint constraint(0, normal_at, normal);
  ConstraintSolver solver;
  solver.add(system, constraint);
  solver.set_projection(projection);
  const Eigen::Vector2d pulled(0.4, 0.05);
  const Eigen::Vector3d start = system.position(0, pulled);
  system.add_force(0, spring_force(
                          pulled, [start](double t) { return (1.0 + 0.3 * t) * start; }, 20.0));
  IntegratorSettings settings;
  settings.newton_iterations = 4;
  Integrator integrator(settings);
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  for (int k = 0; k < steps; ++k) {
    if (constrained) {
      solver.step(integrator, system, dt);
    } else {
      integrator.step(system, dt);
    }
    TangentKinematics tangents;
    sphere.tangent_kinematics(system.coordinates(), system.velocities(), normal_at, tangents);
    const Eigen::Vector3d n = tangents.su.cross(tangents.sv);
    worst = std::max(worst, (n - n.dot(normal) * normal).norm() / n.norm());
  }
  EXPECT_FALSE(solver.last_report().rank_deficient);
  return worst;
}

// The surface normal constraint (constraints/surface_constraints.h) on a swung surface, through
// its tangent kinematics: a normal that the pull turns by a lot without the constraint stays put
// with it, up to Newmark's O(dt^2) error of the non-linear constraint (ratio 4 when dt halves),
// and to the projection's tolerance with the projection on.
TEST(SwungShape, SurfaceNormalConstraintHoldsWhileASpringPulls) {
  const double free = normal_violation(0.01, false, false);
  const double coarse = normal_violation(0.01, true, false);
  const double fine = normal_violation(0.005, true, false);
  const double projected = normal_violation(0.01, true, true);
  std::cout << "swung sphere normal: free deviation " << free << "; held, dt 0.01 " << coarse
            << ", dt 0.005 " << fine << " (ratio " << coarse / fine << "), projected " << projected
            << "\n";
  EXPECT_GT(free, 0.05);           // measured 0.93: the pull turns the free normal
  EXPECT_LT(coarse, 1e-2 * free);  // measured 6.0e-5
  EXPECT_GT(coarse / fine, 3.0);   // second order: measured 4.005
  EXPECT_LT(projected, 1e-10);     // the projection's tolerance 1e-12 on e . N: measured 1.5e-13
}

}  // namespace
}  // namespace dnurbs
