// The Greville rods and sheets of nurbs/shape_generators.h are at rest: the internal force of
// the D-NURBS stretching and bending energy (Terzopoulos 2003, eq. 1.20) vanishes on every control
// point off the border, where a clamped border holds the shape. Evenly spaced control points over
// the same knots are not at rest: that is what the generators fix.

#include <algorithm>

#include <gtest/gtest.h>

#include "dnurbs/core/sparse_matrix.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_curve.h"
#include "dnurbs/dynamics/dnurbs/dnurbs_surface.h"
#include "dnurbs/nurbs/shape_generators.h"
#include "tests/common/dynamics_test_helpers.h"

namespace dnurbs {
namespace {

// The largest |f| over the control points (i, j) off the border of a surface's net, relative to
// the size of the terms that cancel in it, max_i sum_j |K_ij q_j|: the force is a sum of O(100)
// products, so round-off leaves about 1e-15 of that.
double interior_force(const DNurbsSurface& model) {
  const NurbsSurface& s = model.initial_surface();
  const Eigen::VectorXd q = model.initial_coordinates();
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model.coordinate_count());
  model.add_internal_force(q, force);
  const SparseMatrix& stiffness = model.constant_matrices()->stiffness;
  const double scale = (stiffness.cwiseAbs() * q.cwiseAbs()).maxCoeff();
  double largest = 0.0;
  for (int i = 1; i + 1 < s.control_point_count_u(); ++i) {
    for (int j = 1; j + 1 < s.control_point_count_v(); ++j) {
      largest = std::max(largest, force.segment<3>(s.control_point_index(i, j) * 3).norm());
    }
  }
  return largest / scale;
}

TEST(GeneratedShapesAtRest, GrevilleSheetFeelsNoInternalForceOffItsBorder) {
  for (const int degree : {2, 3, 4}) {
    const NurbsSurface sheet = greville_plane({3, 2}, {9, 7}, {degree, degree}, {1, -1, 0.5});
    const DNurbsSurface model(sheet, test::plate_under_tension());
    EXPECT_LT(interior_force(model), 1e-13) << "degree " << degree;
    const DNurbsSurface finer(split_spans(sheet, {2, 3}), test::plate_under_tension());
    EXPECT_LT(interior_force(finer), 1e-13) << "split, degree " << degree;

    // The same knots with evenly spaced control points: the sheet is pulled in its plane
    Eigen::MatrixX3d even = sheet.control_points();
    for (int i = 0; i < 9; ++i) {
      for (int j = 0; j < 7; ++j) {
        even.row(sheet.control_point_index(i, j)) << 1 + 3.0 * i / 8, -1 + 2.0 * j / 6, 0.5;
      }
    }
    const DNurbsSurface uneven(NurbsSurface(sheet.knots_u(), sheet.knots_v(), even),
                               test::plate_under_tension());
    EXPECT_GT(interior_force(uneven), 1e-4) << "degree " << degree;
  }
}

TEST(GeneratedShapesAtRest, GrevilleRodFeelsNoInternalForceOffItsEnds) {
  DNurbsCurveMaterial material;
  material.tension = 3.0;
  material.rigidity = 0.4;
  for (const int degree : {1, 2, 3, 5}) {
    const NurbsCurve rod = greville_line({0, 1, 2}, {2, -1, 3}, 10, degree);
    const DNurbsCurve model(rod, material);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(model.coordinate_count());
    const Eigen::VectorXd q = model.initial_coordinates();
    model.add_internal_force(q, force);
    const SparseMatrix& stiffness = model.constant_matrices()->stiffness;
    const double scale = (stiffness.cwiseAbs() * q.cwiseAbs()).maxCoeff();
    EXPECT_LT(force.segment(3, force.size() - 6).cwiseAbs().maxCoeff() / scale, 1e-13) << degree;
  }
}

}  // namespace
}  // namespace dnurbs
