// dnurbs::Error -> dnurbs.Error (a ValueError), with the library's message.

#include <pybind11/pybind11.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene_simulation.h"
#include "python/src/bindings.h"

namespace dnurbs::python {

void bind_errors(py::module_& module) {
  // pybind11 tries the most recently registered translator first: the base class goes first.
  const auto error = py::register_exception<Error>(module, "Error", PyExc_ValueError);
  error.doc() =
      "Bad input or an unrecoverable failure in the dnurbs library (a ValueError); the message "
      "names the offending value, as the C++ library's dnurbs::Error does.";
  const auto diverged =
      py::register_exception<SimulationDiverged>(module, "SimulationDiverged", error.ptr());
  diverged.doc() =
      "A simulation step diverged (a non-finite state or an energy beyond the energy budget); "
      "the simulation is back at its last good state. A subclass of dnurbs.Error.";
}

}  // namespace dnurbs::python
