// Elimination of fixed coordinates: the free index maps and the reduced matrix against a dense
// selection of the free rows and columns.

#include "dnurbs/core/fixed_coordinates.h"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

TEST(FreeCoordinates, MapsAndReducedMatrixSelectTheFreeRowsAndColumns) {
  const FreeCoordinates free(6, {4, 1, 4});
  EXPECT_EQ(free.free_count(), 4);
  EXPECT_EQ(free.free_unknowns(), (std::vector<int>{0, 2, 3, 5}));
  EXPECT_EQ(free.free_index(1), -1);
  EXPECT_EQ(free.free_index(5), 3);
  Eigen::MatrixXd dense(6, 6);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      dense(i, j) = (i + 1) * 10 + j;
    }
  }
  const SparseMatrix sparse = dense.sparseView();
  const Eigen::MatrixXd reduced = free.reduce(sparse);
  ASSERT_EQ(reduced.rows(), 4);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_EQ(reduced(i, j), dense(free.free_unknown(i), free.free_unknown(j)));
    }
  }
  // Nothing fixed: the matrix itself
  EXPECT_EQ(Eigen::MatrixXd(FreeCoordinates(6, {}).reduce(sparse)), dense);
}

TEST(FreeCoordinates, AnIndexOutOfRangeIsNamed) {
  try {
    FreeCoordinates(3, {0, 7});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("7 is outside 0..2"), std::string::npos);
  }
}

}  // namespace
}  // namespace dnurbs
