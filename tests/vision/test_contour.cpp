#include "dnurbs/vision/contour.h"

#include <gtest/gtest.h>

namespace dnurbs {
namespace {

Contour polygon(std::initializer_list<std::pair<double, double>> points) {
  Contour contour(static_cast<Eigen::Index>(points.size()), 2);
  Eigen::Index i = 0;
  for (const auto& [x, y] : points) {
    contour.row(i++) << x, y;
  }
  return contour;
}

const Contour square_contour = polygon({{0, 0}, {2, 0}, {2, 2}, {0, 2}});

TEST(Contour, SignedAreaIsPositiveCounterClockwise) {
  EXPECT_DOUBLE_EQ(signed_area(square_contour), 4.0);
  EXPECT_DOUBLE_EQ(signed_area(square_contour.colwise().reverse()), -4.0);
}

TEST(Contour, WindingNumberCountsLoopsWithTheirOrientation) {
  const Contour hole = polygon({{0.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}, {1.5, 0.5}});  // clockwise
  EXPECT_EQ(winding_number({square_contour}, Eigen::Vector2d(1.0, 0.2)), 1);
  EXPECT_EQ(winding_number({square_contour, hole}, Eigen::Vector2d(1.0, 1.0)), 0);
  EXPECT_EQ(winding_number({square_contour, hole}, Eigen::Vector2d(1.0, 0.2)), 1);
  EXPECT_EQ(winding_number({square_contour, square_contour}, Eigen::Vector2d(1.0, 1.0)), 2);
  EXPECT_EQ(winding_number({square_contour}, Eigen::Vector2d(3.0, 1.0)), 0);
}

TEST(Contour, IntersectionTestFindsCrossingsTouchesAndFolds) {
  EXPECT_FALSE(contours_intersect({square_contour}));
  const Contour nested = polygon({{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}});
  EXPECT_FALSE(contours_intersect({square_contour, nested}));
  const Contour bow_tie = polygon({{0, 0}, {2, 2}, {2, 0}, {0, 2}});
  EXPECT_TRUE(contours_intersect({bow_tie}));
  const Contour crossing = polygon({{1, 1}, {3, 1}, {3, 3}, {1, 3}});
  EXPECT_TRUE(contours_intersect({square_contour, crossing}));
  const Contour touching = polygon({{2, 1}, {3, 0}, {3, 2}});  // a vertex on the square's edge
  EXPECT_TRUE(contours_intersect({square_contour, touching}));
  const Contour fold = polygon({{0, 0}, {2, 0}, {1, 0}, {1, 1}});  // doubles back along itself
  EXPECT_TRUE(contours_intersect({fold}));
  const Contour far_away = polygon({{5, 5}, {6, 5}, {6, 6}});
  EXPECT_FALSE(contours_intersect({square_contour, far_away}));
}

}  // namespace
}  // namespace dnurbs
