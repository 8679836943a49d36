#include "dnurbs/surface/deformation_field.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/primitive_shapes.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/parametric_surface_tessellation.h"
#include "dnurbs/surface/restricted_mesh.h"

namespace dnurbs {
namespace {

ParameterDomain rectangle(double u_min, double u_max, double v_min, double v_max) {
  ParameterDomain domain;
  domain.u_min = u_min;
  domain.u_max = u_max;
  domain.v_min = v_min;
  domain.v_max = v_max;
  return domain;
}

TEST(SampledVectorField, ReproducesBilinearFieldsAndItsNodes) {
  const ParameterDomain domain = rectangle(-1.0, 2.0, 0.5, 1.5);
  const VectorField bilinear = [](double u, double v) {
    return Eigen::Vector3d(1.0 + 2.0 * u - v, 3.0 * u * v, -0.5 + v + 0.25 * u * v);
  };
  const SampledVectorField field = SampledVectorField::sample(domain, 4, 6, bilinear);
  for (int i = 0; i <= 30; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const double u = domain.u_at(i / 30.0);
      const double v = domain.v_at(j / 20.0);
      // Bilinear interpolation is exact for a bilinear field, up to rounding of sums of O(10)
      EXPECT_LT((field(u, v) - bilinear(u, v)).norm(), 1e-14) << u << ", " << v;
    }
  }
  // Outside an open direction the field is clamped to its edge
  EXPECT_LT((field(-5.0, 0.5) - bilinear(-1.0, 0.5)).norm(), 1e-14);
}

TEST(SampledVectorField, WrapsAlongAPeriodicDirection) {
  ParameterDomain domain = rectangle(0.0, 1.0, 0.0, 2.0 * std::numbers::pi);
  domain.periodic_v = true;
  const SampledVectorField field = SampledVectorField::sample(domain, 3, 8, [](double u, double v) {
    return Eigen::Vector3d(std::cos(v), std::sin(v), u);
  });
  EXPECT_EQ(field.samples().rows(), 3 * 8);
  for (const double u : {0.0, 0.3, 1.0}) {
    // v_max is v_min again; beyond it the field repeats (rounding of the wrapped parameter)
    EXPECT_LT((field(u, domain.v_max) - field(u, domain.v_min)).norm(), 1e-15);
    EXPECT_LT((field(u, 0.4 + domain.v_max) - field(u, 0.4)).norm(), 1e-14);
    // The last cell interpolates between the last node and the first
    const double last = domain.v_at(7.5 / 8.0);
    const Eigen::Vector3d expected =
        0.5 * (field.samples().row(7).transpose() + field.samples().row(0).transpose());
    EXPECT_LT((field(0.0, last) - expected).norm(), 1e-14);
  }
}

TEST(DeformationField, CascadeOfConstantAndAddVectorFollowsSeedEquations) {
  // Goldenstein et al. 2005, eqs. 3-4: p^k = p^(k-1) + q_k V_pc_k, from the mean p^0 = V_mean
  const VectorField mean = [](double u, double v) { return Eigen::Vector3d(u, v, 0.0); };
  const VectorField pc0 = [](double u, double v) { return Eigen::Vector3d(0.0, 0.0, u * v); };
  const VectorField pc1 = [](double u, double v) {
    return Eigen::Vector3d(std::sin(u), 0.0, std::cos(v));
  };
  DeformationField field;
  field.constant(mean).add_vector(pc0, 0).add_vector(pc1, 1);
  EXPECT_EQ(field.stage_count(), 3);
  EXPECT_EQ(field.parameter_count(), 2);
  EXPECT_EQ(field.stage_kind(0), DeformationKind::kConstant);
  const Eigen::Vector2d q(0.7, -1.3);
  const double u = 0.3;
  const double v = 0.8;
  const Eigen::Vector3d expected = mean(u, v) + q(0) * pc0(u, v) + q(1) * pc1(u, v);
  // The constant stage ignores the input
  EXPECT_LT((field.apply(q, u, v, Eigen::Vector3d(9.0, 9.0, 9.0)) - expected).norm(), 1e-15);
  const Eigen::Matrix3Xd jacobian = field.parameter_jacobian(u, v);
  ASSERT_EQ(jacobian.cols(), 2);
  EXPECT_LT((jacobian.col(0) - pc0(u, v)).norm(), 0.0 + 1e-300);
  EXPECT_LT((jacobian.col(1) - pc1(u, v)).norm(), 0.0 + 1e-300);
  // p is affine in q: a difference quotient reproduces the Jacobian up to rounding of p (~1e-16
  // over a step of 1e-3)
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector2d step = q;
    step(k) += 1e-3;
    const Eigen::Vector3d difference = (field.apply(step, u, v) - field.apply(q, u, v)) / 1e-3;
    EXPECT_LT((difference - jacobian.col(k)).norm(), 1e-12);
  }
  // A constant stage after AddVector forgets the parameters before it
  DeformationField reset = field;
  reset.constant(mean);
  EXPECT_LT((reset.apply(q, u, v) - mean(u, v)).norm(), 1e-300);
  EXPECT_EQ(reset.parameter_jacobian(u, v).norm(), 0.0);
}

// Displaces the sphere outwards by q_0 times a bump sampled on a 9 x 16 grid (a field of the
// sphere point, so single-valued at the poles) and by a fixed unparameterized shift in z.
ParametricSurface bumped_sphere(double q0) {
  const ParametricSurface sphere_surface = parametric_surface(sphere(1.0));
  const NurbsSurface nurbs = sphere(1.0);
  const SampledVectorField bump =
      SampledVectorField::sample(sphere_surface.domain(), 9, 16, [nurbs](double u, double v) {
        const Eigen::Vector3d x = nurbs.point(u, v);
        return Eigen::Vector3d(std::exp(-4.0 * (x - Eigen::Vector3d(1.0, 0.0, 0.0)).squaredNorm()) *
                               x);
      });
  DeformationField field;
  field.add_vector(bump, 0).add_vector(
      [](double, double) { return Eigen::Vector3d(0.0, 0.0, 0.25); });
  return deformed_surface(sphere_surface, field, Eigen::VectorXd::Constant(1, q0));
}

std::map<std::pair<double, double>, Eigen::Vector3d> by_parameter(const TriangleMesh& mesh) {
  std::map<std::pair<double, double>, Eigen::Vector3d> points;
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    points[{mesh.uv(k, 0), mesh.uv(k, 1)}] = mesh.vertices.row(k).transpose();
  }
  return points;
}

TEST(DeformationField, AgreesAtSharedParametersAcrossResolutions) {
  const ParametricSurface surface = bumped_sphere(0.4);
  const TriangleMesh coarse = tessellate_surface(surface, 6, 10);
  const TriangleMesh fine = tessellate_surface(surface, 12, 20);
  RestrictedMesh adaptive(surface, 6, 10);
  adaptive.refine(surface_error_criterion(surface, 2e-3));
  const TriangleMesh adapted = adaptive.to_triangle_mesh();
  const auto coarse_points = by_parameter(coarse);
  int shared_fine = 0;
  int shared_adaptive = 0;
  for (const auto& [mesh, shared] :
       {std::pair{&fine, &shared_fine}, {&adapted, &shared_adaptive}}) {
    for (const auto& [uv, x] : by_parameter(*mesh)) {
      const auto found = coarse_points.find(uv);
      if (found != coarse_points.end()) {
        // The same (u, v) through the same cascade: equal (far inside 1e-14)
        EXPECT_LT((found->second - x).norm(), 1e-14) << uv.first << ", " << uv.second;
        ++*shared;
      }
    }
  }
  // Every coarse vertex is a vertex of both finer meshes (poles: one each)
  EXPECT_EQ(shared_fine, coarse.vertex_count());
  EXPECT_EQ(shared_adaptive, coarse.vertex_count());
  // The deformation moved the points: the bump at (1, 0, 0) and the shift in z
  const Eigen::Vector3d equator = surface.point(0.5, 0.0);
  EXPECT_NEAR(equator.x(), 1.0 + 0.4, 1e-12);  // bump value exp(0) at a node, times q_0
  EXPECT_NEAR(equator.z(), 0.25, 1e-12);
}

TEST(DeformationField, GeometryImageReproducesItsSamplesAtItsResolution) {
  // Goldenstein et al. 2005, eq. 2: a rigid model as a constant field of a sampled geometry image
  const ParametricSurface torus = parametric_surface(periodic_torus(3.0, 1.0));
  const SampledVectorField image = SampledVectorField::sample(
      torus.domain(), 12, 8, [&](double u, double v) { return torus.point(u, v); });
  DeformationField field;
  field.constant(image);
  const ParametricSurface surface =
      deformation_field_surface(torus.domain(), field, Eigen::VectorXd());
  const TriangleMesh mesh = tessellate_surface(surface, 12, 8);
  ASSERT_EQ(mesh.vertex_count(), 12 * 8);
  for (int k = 0; k < mesh.vertex_count(); ++k) {
    // a node's bilinear weights are 1 and 0 up to rounding of the located parameter
    EXPECT_LT((mesh.vertices.row(k) - image.samples().row(k)).norm(), 1e-14) << "vertex " << k;
  }
}

TEST(DeformationField, InvalidInputNamesTheValue) {
  const ParameterDomain domain = rectangle(0.0, 1.0, 0.0, 1.0);
  EXPECT_THROW(SampledVectorField(domain, 1, 3, Eigen::MatrixX3d::Zero(3, 3)), Error);
  EXPECT_THROW(SampledVectorField(domain, 2, 3, Eigen::MatrixX3d::Zero(5, 3)), Error);
  DeformationField field;
  EXPECT_THROW(field.add_vector(VectorField{}, 0), Error);
  EXPECT_THROW(field.add_vector([](double, double) { return Eigen::Vector3d::Zero(); }, -1), Error);
  field.add_vector([](double, double) { return Eigen::Vector3d::UnitX(); }, 2);
  try {
    field.apply(Eigen::VectorXd::Zero(2), 0.0, 0.0);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("uses 3"), std::string::npos) << error.what();
  }
  EXPECT_THROW(deformed_surface(parametric_surface(sphere(1.0)), field, Eigen::VectorXd::Zero(1)),
               Error);
}

}  // namespace
}  // namespace dnurbs
