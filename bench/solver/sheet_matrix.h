#pragma once
// Test matrices of bench/solver: the scalar step matrix of a clamped bicubic D-NURBS sheet and
// the basis functions of a spring on it.

#include <Eigen/SparseCore>
#include <array>

#include "dnurbs/nurbs/knot_vector.h"

namespace dnurbs::bench {

/// Scalar (per coordinate) matrices of a side by side clamped bicubic sheet over [0, 1]^2 and the
/// central-difference step matrix built from them.
struct SheetMatrix {
  int side = 0;
  KnotVector knots{3, {0, 0, 0, 0, 1, 1, 1, 1}};
  /// A = M / dt^2 + D / (2 dt) + K, the matrix of the semi-implicit central step (Terzopoulos,
  /// Deformable Models: Classic, Topology-Adaptive and Generalized Formulations, eq. 1.13),
  /// side^2 by side^2, both triangles; nodes (i, j) at row i side + j, coupled when |di| <= 3 and
  /// |dj| <= 3 (49 entries per column inside).
  Eigen::SparseMatrix<double> step_matrix;
};

/// M = integral mu N N^T, D = (gamma / mu) M, K = integral a10 N_u N_u^T + a01 N_v N_v^T + b20
/// N_uu N_uu^T + 2 b11 N_uv N_uv^T + b02 N_vv N_vv^T (thin plate under tension, Terzopoulos,
/// Deformable Models, eq. 1.20), integrated exactly by 4-point Gauss-Legendre per knot span in each
/// direction; mu = 1, gamma = 1, a = 1, b = 1e-3, dt = 1/60.
SheetMatrix make_sheet_matrix(int side);

/// The 16 non-zero bicubic basis functions N_i(u) N_j(v) of the sheet at (u, v) and their rows.
struct SpringBasis {
  std::array<int, 16> rows{};
  std::array<double, 16> values{};
};
SpringBasis spring_basis(const SheetMatrix& sheet, double u, double v);

}  // namespace dnurbs::bench
