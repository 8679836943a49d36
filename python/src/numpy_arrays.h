#pragma once
// NumPy arrays in and out of the dnurbs Python module.
//
// In: every array argument is read through these functions, which accept any real dtype
// (float, int, unsigned), any memory order and any strides (C order, Fortran order, slices with
// steps) and throw dnurbs::Error (ValueError in Python) naming the argument and the shape it
// should have; a non-real dtype (complex, object, strings) is a TypeError naming the dtype.
// Inputs are copied into the library's own storage (the library's shapes are values).
//
// Out: results the library keeps (control points, weights, knots, coordinates) are returned as
// read-only views of the library's memory, kept alive by the Python object that owns them (no
// copy; np.shares_memory holds between two reads); results computed by a call are new arrays.

#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <Eigen/Core>

#include "dnurbs/core/error.h"

namespace dnurbs::python {

namespace py = pybind11;

/// `value` (an array, a nested list or a number) as a float64 array: the array itself if it is
/// one of float64 (any strides), else a cast copy. Throws TypeError naming `name` if its dtype is
/// not real (bool, int, unsigned or float).
py::array_t<double> real_array(const py::object& value, const std::string& name);

/// `value` (shape (rows, columns)) as an Eigen matrix; rows < 0 (columns < 0) accepts any row
/// (column) count, and a
/// 1-D array of `columns` values is read as one row when `one_row_ok`. Throws Error naming
/// `name` and both shapes otherwise.
Eigen::MatrixXd matrix_from_array(const py::object& value, const std::string& name, long rows,
                                  long columns, bool one_row_ok = false);
/// `value` (shape (size,), size < 0: any) as an Eigen vector; Error naming `name` otherwise.
Eigen::VectorXd vector_from_array(const py::object& value, const std::string& name, long size = -1);
/// `value` (shape (size,)) as a std::vector; Error naming `name` otherwise.
std::vector<double> list_from_array(const py::object& value, const std::string& name);
/// `value` (shape (rows, columns)) of integers as an Eigen matrix; Error naming `name` if it has
/// another shape or holds values that are not integers.
Eigen::MatrixXi index_matrix_from_array(const py::object& value, const std::string& name,
                                        long columns);

/// A material parameter: u of a curve (a number or (1,)) or (u, v) of a surface ((2,)), as
/// (u, v) with v = 0 for curves; Error naming the shape otherwise.
Eigen::Vector2d material_parameter(const py::object& value);

/// A C-contiguous float64 copy (or view) of `value` of any shape (parameter arrays); TypeError
/// as real_array.
py::array_t<double, py::array::c_style> parameter_array(const py::object& value,
                                                        const std::string& name);
/// An array argument read as `count` items: scalars (item_size 0, any shape) or vectors along
/// the last axis (item_size > 0, shape (..., item_size)); C-contiguous float64.
struct ItemArray {
  py::array_t<double, py::array::c_style> values;
  std::vector<py::ssize_t> shape;  ///< the shape of the items (the array's without the last axis)
  py::ssize_t count = 0;
  py::ssize_t item_size = 1;  ///< values per item
  const double* item(py::ssize_t i) const { return values.data() + i * item_size; }
};
/// `value` as items of `item_size` values (0: scalars); Error naming `name` if its last axis is
/// not item_size long; TypeError as real_array.
ItemArray item_array(const py::object& value, const std::string& name, py::ssize_t item_size);
/// Two scalar item arrays broadcast against each other (NumPy rules); Error naming both shapes
/// if they do not broadcast.
std::pair<ItemArray, ItemArray> broadcast_items(const py::object& u, const py::object& v);
/// A new float64 array of shape items.shape + tail, for one result of shape `tail` per item.
py::array_t<double> new_result(const ItemArray& items, const std::vector<py::ssize_t>& tail);

/// A read-only array over `data` (column-major Eigen storage of double or int) with shape
/// (rows, columns) that keeps `owner` alive.
template <typename Scalar>
py::array read_only_view(const Scalar* data, py::ssize_t rows, py::ssize_t columns,
                         const py::handle& owner) {
  const auto item = static_cast<py::ssize_t>(sizeof(Scalar));
  py::array view(py::dtype::of<Scalar>(), {rows, columns}, {item, item * rows}, data, owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}
/// A read-only 1-D array over `data` of `size` values that keeps `owner` alive.
py::array read_only_view(const double* data, py::ssize_t size, const py::handle& owner);

/// A new (rows, columns) float64 array holding a copy of `matrix`.
py::array_t<double> array_from_matrix(const Eigen::MatrixXd& matrix);
/// A new (size,) float64 array holding a copy of `vector`.
py::array_t<double> array_from_vector(const Eigen::VectorXd& vector);
/// A new (rows, columns) int32 array holding a copy of `matrix`.
py::array_t<int> array_from_index_matrix(const Eigen::MatrixXi& matrix);

}  // namespace dnurbs::python
