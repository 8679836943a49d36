#include "python/src/sparse_matrices.h"

#include <algorithm>

#include <pybind11/numpy.h>

#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

py::object sparse_matrix_to_python(const SparseMatrix& matrix, bool dense) {
  if (dense) {
    return array_from_matrix(Eigen::MatrixXd(matrix));
  }
  SparseMatrix compressed = matrix;
  compressed.makeCompressed();
  const auto non_zeros = static_cast<py::ssize_t>(compressed.nonZeros());
  py::array_t<double> data(non_zeros);
  py::array_t<int> indices(non_zeros);
  py::array_t<int> pointers(compressed.cols() + 1);
  std::copy_n(compressed.valuePtr(), non_zeros, data.mutable_data());
  std::copy_n(compressed.innerIndexPtr(), non_zeros, indices.mutable_data());
  std::copy_n(compressed.outerIndexPtr(), compressed.cols() + 1, pointers.mutable_data());
  const py::tuple shape = py::make_tuple(compressed.rows(), compressed.cols());
  py::module_ scipy_sparse;
  try {
    scipy_sparse = py::module_::import("scipy.sparse");
  } catch (const py::error_already_set& error) {
    if (!error.matches(PyExc_ImportError)) {
      throw;
    }
    return py::make_tuple(data, indices, pointers, shape);
  }
  return scipy_sparse.attr("csc_matrix")(py::make_tuple(data, indices, pointers),
                                         py::arg("shape") = shape);
}

}  // namespace dnurbs::python
