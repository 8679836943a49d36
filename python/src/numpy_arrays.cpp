#include "python/src/numpy_arrays.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dnurbs/core/error.h"

namespace dnurbs::python {

namespace {

// "(3, 4)" for an array of that shape.
std::string shape_text(const py::array& array) {
  std::ostringstream text;
  text << "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    text << (d > 0 ? ", " : "") << array.shape(d);
  }
  text << (array.ndim() == 1 ? ",)" : ")");
  return text.str();
}

// "(n, 3)" or "(4, 3)" for the expected shape.
std::string expected_text(long rows, long columns) {
  std::ostringstream text;
  text << "(";
  if (rows < 0) {
    text << "n";
  } else {
    text << rows;
  }
  text << ", ";
  if (columns < 0) {
    text << "m";
  } else {
    text << columns;
  }
  text << ")";
  return text.str();
}

}  // namespace

py::array_t<double> real_array(const py::object& value, const std::string& name) {
  const py::array array = py::array::ensure(value);
  if (!array) {
    throw py::type_error(name + " must be an array of real numbers");
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    throw py::type_error(name + " must be an array of real numbers, got dtype " +
                         std::string(py::str(array.dtype())));
  }
  return py::array_t<double>::ensure(array);
}

Eigen::MatrixXd matrix_from_array(const py::object& value, const std::string& name, long rows,
                                  long columns, bool one_row_ok) {
  const py::array_t<double> values = real_array(value, name);
  const bool one_row = one_row_ok && values.ndim() == 1 && values.shape(0) == columns;
  const bool matches = values.ndim() == 2 && (columns < 0 || values.shape(1) == columns) &&
                       (rows < 0 || values.shape(0) == rows);
  if (!one_row && !matches) {
    const std::string expected =
        one_row_ok ? "(" + std::to_string(columns) + ",)" : expected_text(rows, columns);
    throw make_error(name, " must have shape ", expected, ", got ", shape_text(values));
  }
  if (one_row) {
    Eigen::MatrixXd matrix(1, columns);
    const auto view = values.unchecked<1>();
    for (long j = 0; j < columns; ++j) {
      matrix(0, j) = view(j);
    }
    return matrix;
  }
  Eigen::MatrixXd matrix(values.shape(0), values.shape(1));
  const auto view = values.unchecked<2>();
  for (long j = 0; j < matrix.cols(); ++j) {
    for (long i = 0; i < matrix.rows(); ++i) {
      matrix(i, j) = view(i, j);
    }
  }
  return matrix;
}

Eigen::VectorXd vector_from_array(const py::object& value, const std::string& name, long size) {
  const py::array_t<double> values = real_array(value, name);
  if (values.ndim() != 1 || (size >= 0 && values.shape(0) != size)) {
    if (size >= 0) {
      throw make_error(name, " must have shape (", size, ",), got ", shape_text(values));
    }
    throw make_error(name, " must be one-dimensional, got shape ", shape_text(values));
  }
  Eigen::VectorXd vector(values.shape(0));
  const auto view = values.unchecked<1>();
  for (long i = 0; i < vector.size(); ++i) {
    vector[i] = view(i);
  }
  return vector;
}

std::vector<double> list_from_array(const py::object& value, const std::string& name) {
  const Eigen::VectorXd vector = vector_from_array(value, name);
  return {vector.data(), vector.data() + vector.size()};
}

Eigen::MatrixXi index_matrix_from_array(const py::object& value, const std::string& name,
                                        long columns) {
  const Eigen::MatrixXd values = matrix_from_array(value, name, -1, columns);
  Eigen::MatrixXi indices(values.rows(), values.cols());
  for (long i = 0; i < values.rows(); ++i) {
    for (long j = 0; j < columns; ++j) {
      const double value = values(i, j);
      if (!(std::abs(value) < 2e9) || value != std::round(value)) {
        throw make_error(name, "[", i, ", ", j, "] is ", value, ", must be an integer index");
      }
      indices(i, j) = static_cast<int>(value);
    }
  }
  return indices;
}

Eigen::Vector2d material_parameter(const py::object& value) {
  const py::array_t<double> u = real_array(value, "u");
  if (u.ndim() > 1 || u.size() < 1 || u.size() > 2) {
    throw make_error("u must be a number, (1,) or (2,), got shape ", shape_text(u));
  }
  const double* values = py::array_t<double, py::array::c_style>::ensure(u).data();
  return {values[0], u.size() == 2 ? values[1] : 0.0};
}

py::array_t<double, py::array::c_style> parameter_array(const py::object& value,
                                                        const std::string& name) {
  return py::array_t<double, py::array::c_style>::ensure(real_array(value, name));
}

ItemArray item_array(const py::object& value, const std::string& name, py::ssize_t item_size) {
  ItemArray items;
  items.values = parameter_array(value, name);
  items.item_size = std::max<py::ssize_t>(item_size, 1);
  const py::ssize_t dimensions = items.values.ndim();
  if (item_size > 0 && (dimensions == 0 || items.values.shape(dimensions - 1) != item_size)) {
    throw make_error(name, " must have shape (", item_size, ",) or (..., ", item_size, "), got ",
                     shape_text(items.values));
  }
  const py::ssize_t kept = item_size > 0 ? dimensions - 1 : dimensions;
  items.shape.assign(items.values.shape(), items.values.shape() + kept);
  items.count = items.values.size() / items.item_size;
  return items;
}

std::pair<ItemArray, ItemArray> broadcast_items(const py::object& u, const py::object& v) {
  const py::array u_values = real_array(u, "u");
  const py::array v_values = real_array(v, "v");
  py::tuple both;
  try {
    both = py::tuple(py::module_::import("numpy").attr("broadcast_arrays")(u_values, v_values));
  } catch (const py::error_already_set&) {
    throw make_error("u of shape ", shape_text(u_values), " and v of shape ", shape_text(v_values),
                     " do not broadcast to one shape");
  }
  return {item_array(both[0], "u", 0), item_array(both[1], "v", 0)};
}

py::array_t<double> new_result(const ItemArray& items, const std::vector<py::ssize_t>& tail) {
  std::vector<py::ssize_t> shape = items.shape;
  shape.insert(shape.end(), tail.begin(), tail.end());
  return py::array_t<double>(shape);
}

py::array read_only_view(const double* data, py::ssize_t size, const py::handle& owner) {
  py::array view(py::dtype::of<double>(), {size}, {static_cast<py::ssize_t>(sizeof(double))}, data,
                 owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

py::array_t<double> array_from_matrix(const Eigen::MatrixXd& matrix) {
  py::array_t<double> array({matrix.rows(), matrix.cols()});
  auto view = array.mutable_unchecked<2>();
  for (long i = 0; i < matrix.rows(); ++i) {
    for (long j = 0; j < matrix.cols(); ++j) {
      view(i, j) = matrix(i, j);
    }
  }
  return array;
}

py::array_t<double> array_from_vector(const Eigen::VectorXd& vector) {
  py::array_t<double> array(vector.size());
  std::copy(vector.data(), vector.data() + vector.size(), array.mutable_data());
  return array;
}

py::array_t<int> array_from_index_matrix(const Eigen::MatrixXi& matrix) {
  py::array_t<int> array({matrix.rows(), matrix.cols()});
  auto view = array.mutable_unchecked<2>();
  for (long i = 0; i < matrix.rows(); ++i) {
    for (long j = 0; j < matrix.cols(); ++j) {
      view(i, j) = matrix(i, j);
    }
  }
  return array;
}

}  // namespace dnurbs::python
