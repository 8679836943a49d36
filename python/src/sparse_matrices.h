#pragma once
// Sparse matrices of the library (core/sparse_matrix.h, column-major) out to Python:
// scipy.sparse.csc_matrix where SciPy is installed, else the plain CSC arrays; or dense arrays.

#include <pybind11/pybind11.h>

#include "dnurbs/core/sparse_matrix.h"

namespace dnurbs::python {

namespace py = pybind11;

/// `matrix` (rows by columns) as a new dense float64 array when `dense`, else as
/// scipy.sparse.csc_matrix (copies of its data, indices and column pointers), or, without SciPy,
/// the tuple (data (nnz,) float64, indices (nnz,) int32, indptr (columns + 1,) int32,
/// (rows, columns)).
py::object sparse_matrix_to_python(const SparseMatrix& matrix, bool dense);

}  // namespace dnurbs::python
