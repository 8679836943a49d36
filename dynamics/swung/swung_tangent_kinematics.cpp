#include "dnurbs/dynamics/swung/swung_tangent_kinematics.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

void swung_tangent_kinematics(const SwungJacobian& jacobian, const ConstVectorRef& qd,
                              const std::array<Eigen::Vector3d, 6>& rates,
                              TangentKinematics& tangents) {
  if (jacobian.order < 1) {
    throw make_error("swung tangent kinematics need a Jacobian of order >= 1, got order ",
                     jacobian.order);
  }
  const auto iu = static_cast<size_t>(SurfaceQuantity::kU);
  const auto iv = static_cast<size_t>(SurfaceQuantity::kV);
  tangents.su = jacobian.point_derivatives[iu];
  tangents.sv = jacobian.point_derivatives[iv];
  tangents.su_bias = rates[iu];
  tangents.sv_bias = rates[iv];

  // The Jacobian's columns in ascending coordinate order, repeated coordinates merged.
  std::vector<int> order(static_cast<size_t>(jacobian.column_count));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return jacobian.coordinate[static_cast<size_t>(a)] <
           jacobian.coordinate[static_cast<size_t>(b)];
  });
  tangents.columns.clear();
  tangents.ju.setZero(3, jacobian.column_count);
  tangents.jv.setZero(3, jacobian.column_count);
  int count = 0;
  for (const int c : order) {
    const int coordinate = jacobian.coordinate[static_cast<size_t>(c)];
    if (tangents.columns.empty() || tangents.columns.back() != coordinate) {
      tangents.columns.push_back(coordinate);
      ++count;
    }
    tangents.ju.col(count - 1) += jacobian.columns[iu].col(c);
    tangents.jv.col(count - 1) += jacobian.columns[iv].col(c);
  }
  tangents.ju.conservativeResize(3, count);
  tangents.jv.conservativeResize(3, count);

  // Rates S_u' = J_u qd and S_v' = J_v qd over the non-zero columns.
  tangents.su_rate.setZero();
  tangents.sv_rate.setZero();
  for (int c = 0; c < count; ++c) {
    const double rate = qd[tangents.columns[static_cast<size_t>(c)]];
    tangents.su_rate += tangents.ju.col(c) * rate;
    tangents.sv_rate += tangents.jv.col(c) * rate;
  }
}

}  // namespace dnurbs
