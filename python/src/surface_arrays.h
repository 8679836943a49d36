#pragma once
// Evaluation of a parametric surface (NurbsSurface, SwungSurface) on arrays of parameters: u and
// v broadcast against each other (NumPy rules) and one result per parameter pair.

#include <algorithm>

#include "dnurbs/nurbs/nurbs_surface.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

/// One 3-vector function(u, v) per parameter pair: shape broadcast(u, v).shape + (3,).
template <typename Function>
py::array_t<double> vector_per_parameter(const py::object& u, const py::object& v,
                                         const Function& function) {
  const auto [us, vs] = broadcast_items(u, v);
  py::array_t<double> result = new_result(us, {3});
  double* out = result.mutable_data();
  for (py::ssize_t i = 0; i < us.count; ++i) {
    Eigen::Map<Eigen::Vector3d>(out + 3 * i) = function(*us.item(i), *vs.item(i));
  }
  return result;
}

/// Partial derivatives d^(k+l) S / du^k dv^l of `surface` (a class with derivatives(u, v, order,
/// SurfaceDerivatives&)) for k + l <= order: shape broadcast(u, v).shape + (order + 1, order + 1,
/// 3), zero where k + l > order. Throws Error for an order outside 0..kMaxDerivativeOrder.
template <typename Surface>
py::array_t<double> surface_derivative_array(const Surface& surface, const py::object& u,
                                             const py::object& v, int order) {
  const auto [us, vs] = broadcast_items(u, v);
  if (order < 0 || order > kMaxDerivativeOrder) {
    throw make_error("derivative order ", order, " is outside 0..", kMaxDerivativeOrder);
  }
  py::array_t<double> result = new_result(us, {order + 1, order + 1, 3});
  double* out = result.mutable_data();
  std::fill(out, out + result.size(), 0.0);
  SurfaceDerivatives derivatives;
  for (py::ssize_t i = 0; i < us.count; ++i) {
    surface.derivatives(*us.item(i), *vs.item(i), order, derivatives);
    for (int k = 0; k <= order; ++k) {
      for (int l = 0; k + l <= order; ++l) {
        Eigen::Map<Eigen::Vector3d>(out + 3 * ((i * (order + 1) + k) * (order + 1) + l)) =
            derivatives(k, l);
      }
    }
  }
  return result;
}

}  // namespace dnurbs::python
