// The shape side of the triangular D-NURBS model's contract (dynamics/core/model.h), in
// dynamics/triangular/triangular_dnurbs_surface_shape.cpp: domain, parametric surface,
// tessellation, tangent kinematics, and the boundary conditions that fix control points.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "dnurbs/dynamics/triangular/triangular_local_sculpting.h"
#include "dnurbs/dynamics/triangular/triangular_tessellation.h"
#include "triangular_model_helpers.h"

namespace dnurbs {
namespace {

TriangularDNurbsSettings free_weights() {
  TriangularDNurbsSettings settings;
  settings.weight_mode = WeightMode::kFree;
  return settings;
}

TEST(TriangularDNurbsShape, DomainIsTheBoundingBoxAndARectangleHasAParametricSurface) {
  const auto square = test::triangular_basis(
      rectangle_triangulation(Eigen::Vector2d(-1, 2), Eigen::Vector2d(3, 2.5), 4, 2), 2);
  const TriangularDNurbsSurface model(test::curved_triangular_surface(square, true));
  const Eigen::VectorXd q = model.initial_coordinates();
  const ParameterDomain domain = model.parameter_domain(q);
  EXPECT_EQ(domain.u_min, -1.0);
  EXPECT_EQ(domain.u_max, 3.0);
  EXPECT_EQ(domain.v_min, 2.0);
  EXPECT_EQ(domain.v_max, 2.5);
  EXPECT_FALSE(domain.periodic_u || domain.periodic_v || domain.pole_u_min || domain.pole_v_max);
  // The parametric surface is the model's position with the exact normal
  const ParametricSurface surface = model.parametric_surface(q);
  const TriangularNurbsSurface shape = model.surface(q);
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(-1, 2), Eigen::Vector2d(0.3, 2.21),
                                   Eigen::Vector2d(3, 2.5), Eigen::Vector2d(1.7, 2.4)}) {
    EXPECT_EQ(surface.point(u.x(), u.y()), model.position(q, u));
    // (normalized once more by ParametricSurface: rounding 1e-16)
    EXPECT_LT((surface.unit_normal(u.x(), u.y()) - shape.unit_normal(u)).norm(), 1e-15);
    // The difference normal agrees (central differences, step 1e-5 of the extent: 1e-9)
    EXPECT_LT((surface.difference_normal(u.x(), u.y()) - shape.unit_normal(u)).norm(), 1e-7);
  }
  // An L-shape does not fill its box: no rectangular parameterization
  const auto l_shape = test::triangular_basis(l_shape_triangulation(1), 2);
  const TriangularDNurbsSurface l_model(flat_triangular_surface(l_shape));
  EXPECT_EQ(l_model.parameter_domain(l_model.initial_coordinates()).u_max, 2.0);
  EXPECT_THROW(l_model.parametric_surface(l_model.initial_coordinates()), Error);
}

TEST(TriangularDNurbsShape, TessellationIsUniformByResolutionOrAdaptiveByError) {
  const auto basis = test::triangular_basis(l_shape_triangulation(2), 2);  // edges 0.5, 0.71
  const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, false));
  const Eigen::VectorXd q = model.initial_coordinates();
  const int triangles = basis->triangulation().triangle_count();
  // Width 2 and 8 segments: edges at most 0.25, so the longest domain edge sqrt(2)/2 needs
  // ceil(2.83) = 3 subdivisions
  ModelTessellationSettings settings;
  settings.segments_u = 8;
  settings.segments_v = 8;
  TriangleMesh mesh = tessellate_model(model, q, settings, "l");
  EXPECT_EQ(mesh.triangle_count(), triangles * 9);
  EXPECT_EQ(mesh.name, "l");
  // The model's own subdivisions override the resolution
  TriangularDNurbsSettings own;
  own.tessellation_subdivisions = 2;
  const TriangularDNurbsSurface two(test::curved_triangular_surface(basis, false), {}, own);
  EXPECT_EQ(tessellate_model(two, q, settings).triangle_count(), triangles * 4);
  // Adaptive: the library's adaptive mesh, from the caller's max_error and max_level or from
  // the model's own
  settings.max_error = 2e-3;
  const TriangleMesh adaptive = tessellate_model(model, q, settings);
  const TriangleMesh expected =
      tessellate_triangular_surface_adaptive(model.surface(q), 2e-3, settings.max_level);
  EXPECT_EQ(adaptive.vertices, expected.vertices);
  EXPECT_EQ(adaptive.triangles, expected.triangles);
  own.tessellation_max_error = 2e-3;
  own.tessellation_max_level = settings.max_level;
  const TriangularDNurbsSurface adaptive_model(test::curved_triangular_surface(basis, false), {},
                                               own);
  settings.max_error = 0.0;
  EXPECT_EQ(tessellate_model(adaptive_model, q, settings).triangle_count(),
            adaptive.triangle_count());
  // Bad settings name the value
  own.tessellation_max_error = -1.0;
  EXPECT_THROW(TriangularDNurbsSurface(flat_triangular_surface(basis), {}, own), Error);
  own.tessellation_max_error = 0.0;
  own.tessellation_subdivisions = 2000;
  EXPECT_THROW(TriangularDNurbsSurface(flat_triangular_surface(basis), {}, own), Error);
}

// S_u, S_v, their Jacobians, rates and Jdot qd against differences of the model's own
// positions and tangents, with fixed and free weights on a rational surface.
TEST(TriangularDNurbsShape, TangentKinematicsMatchDifferences) {
  const auto basis = test::triangular_basis(l_shape_triangulation(1), 2);
  for (const bool free : {false, true}) {
    const TriangularDNurbsSurface model(test::curved_triangular_surface(basis, true), {},
                                        free ? free_weights() : TriangularDNurbsSettings{});
    const Eigen::VectorXd q = model.initial_coordinates();
    const Eigen::VectorXd qd = test::random_velocity(q.size(), 7);
    for (const Eigen::Vector2d& u :
         {Eigen::Vector2d(0.3, 0.2), Eigen::Vector2d(1.62, 0.71), Eigen::Vector2d(0.45, 1.5)}) {
      TangentKinematics tangents;
      model.tangent_kinematics(q, qd, u, tangents);
      // S_u, S_v against differences of x in u and v (truncation h^2 |x'''|, rounding 1e-16/h)
      const double h = 1e-6;
      const Eigen::Vector2d du(h, 0.0);
      const Eigen::Vector2d dv(0.0, h);
      EXPECT_LT(
          (tangents.su - (model.position(q, u + du) - model.position(q, u - du)) / (2 * h)).norm(),
          1e-8);
      EXPECT_LT(
          (tangents.sv - (model.position(q, u + dv) - model.position(q, u - dv)) / (2 * h)).norm(),
          1e-8);
      // J_u, J_v column by column against differences of the tangents in the coordinates
      ASSERT_TRUE(std::is_sorted(tangents.columns.begin(), tangents.columns.end()));
      ASSERT_EQ(tangents.ju.cols(), static_cast<Eigen::Index>(tangents.columns.size()));
      Eigen::MatrixXd ju = Eigen::MatrixXd::Zero(3, q.size());
      Eigen::MatrixXd jv = Eigen::MatrixXd::Zero(3, q.size());
      for (size_t k = 0; k < tangents.columns.size(); ++k) {
        ju.col(tangents.columns[k]) = tangents.ju.col(static_cast<Eigen::Index>(k));
        jv.col(tangents.columns[k]) = tangents.jv.col(static_cast<Eigen::Index>(k));
      }
      TangentKinematics plus;
      TangentKinematics minus;
      const double hq = 1e-6;
      double error = 0.0;
      for (Eigen::Index k = 0; k < q.size(); ++k) {
        Eigen::VectorXd qp = q;
        Eigen::VectorXd qm = q;
        qp[k] += hq;
        qm[k] -= hq;
        model.tangent_kinematics(qp, qd, u, plus);
        model.tangent_kinematics(qm, qd, u, minus);
        error = std::max(error, (ju.col(k) - (plus.su - minus.su) / (2 * hq)).norm());
        error = std::max(error, (jv.col(k) - (plus.sv - minus.sv) / (2 * hq)).norm());
      }
      // Truncation hq^2 |d^3 S_u / dq^3| and rounding 1e-16 / hq: below 1e-8
      EXPECT_LT(error, 1e-7) << "free " << free << " at " << u.transpose();
      EXPECT_LT((tangents.su_rate - ju * qd).norm(), 1e-13 * (1.0 + tangents.su_rate.norm()));
      EXPECT_LT((tangents.sv_rate - jv * qd).norm(), 1e-13 * (1.0 + tangents.sv_rate.norm()));
      // Jdot qd: the second derivative of S_u along q + t qd (truncation t^2, rounding 1e-16/t^2)
      const double t = 1e-4;
      model.tangent_kinematics(q + t * qd, qd, u, plus);
      model.tangent_kinematics(q - t * qd, qd, u, minus);
      const Eigen::Vector3d su_second = (plus.su - 2.0 * tangents.su + minus.su) / (t * t);
      const Eigen::Vector3d sv_second = (plus.sv - 2.0 * tangents.sv + minus.sv) / (t * t);
      EXPECT_LT((tangents.su_bias - su_second).norm(), 1e-5 * (1.0 + su_second.norm()));
      EXPECT_LT((tangents.sv_bias - sv_second).norm(), 1e-5 * (1.0 + sv_second.norm()));
      std::cout << "[ tangents ] free " << free << " at " << u.transpose() << ": J error " << error
                << ", Jdot qd error " << (tangents.su_bias - su_second).norm() << " of "
                << su_second.norm() << "\n";
      if (!free) {
        EXPECT_EQ(tangents.su_bias, Eigen::Vector3d::Zero());
      } else {
        EXPECT_GT(su_second.norm(), 1e-2);  // the free-weight term is really exercised
      }
    }
  }
}

TEST(TriangularDNurbsBoundary,
     FixBorderFixesTheBorderControlPointsAndLocalSculptingFreezesTheRest) {
  const auto basis = test::triangular_basis(square_with_hole_triangulation(2), 2);
  TriangularDNurbsSurface model(flat_triangular_surface(basis));
  model.fix_border();
  const std::vector<int> border = border_control_points(*basis);
  ASSERT_EQ(model.fixed_coordinates().size(), 3 * border.size());
  for (size_t k = 0; k < border.size(); ++k) {
    EXPECT_EQ(model.fixed_coordinates()[3 * k], 3 * border[k]);
  }
  // Fixing a point through the contract and the range check
  TriangularDNurbsSurface points(flat_triangular_surface(basis));
  points.fix_point(5);
  EXPECT_EQ(points.fixed_coordinates(), (std::vector<int>{15, 16, 17}));
  EXPECT_THROW(points.fix_point(basis->function_count()), Error);
  // Local sculpting: the frozen count is the complement of the sculpted control points
  TriangularDNurbsSurface sculpted(flat_triangular_surface(basis), {}, free_weights());
  SculptedRegion region;
  region.parameters = {Eigen::Vector2d(0.5, 0.5)};
  const int kept = static_cast<int>(triangular_sculpted_control_points(*basis, region, 1).size());
  EXPECT_EQ(sculpted.freeze_outside(region, 1), basis->function_count() - kept);
  // Free weights: a frozen control point keeps its weight free (gauge weight 0 fixed too)
  EXPECT_EQ(static_cast<int>(sculpted.fixed_coordinates().size()),
            3 * (basis->function_count() - kept) + 1);
  // Lower bounds of the optimizers: every weight at the minimum weight
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(sculpted.velocity_count(),
                                                    -std::numeric_limits<double>::infinity());
  sculpted.coordinate_lower_bounds(lower);
  EXPECT_EQ(lower[sculpted.weight_offset(3)], sculpted.minimum_weight());
  EXPECT_EQ(lower[3 * 4 + 0], -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace dnurbs
