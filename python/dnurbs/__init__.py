"""dnurbs: physics-based geometric design (D-NURBS, deformable superquadrics, grid surfaces).

The compiled kernel is dnurbs._dnurbs; everything it defines is re-exported here. Arrays cross
as NumPy float64 arrays; bad input raises dnurbs.Error (a ValueError) with the library's
message. docs/python.md in the source tree describes the module.
"""

from ._dnurbs import *  # noqa: F401,F403
from ._dnurbs import Error, SimulationDiverged  # noqa: F401

__version__ = "@PROJECT_VERSION@"


def read_log(path):
    """Reads the CSV log of a run (log.csv): returns (columns, values) with columns the list of
    column names ("step", "time", energies, constraint violations, probe coordinates) and
    values a float64 array of shape (#rows, #columns). The log's numbers have 17 significant
    digits, so they read back exactly."""
    import numpy

    with open(path, encoding="utf-8") as log:
        columns = log.readline().strip().split(",")
    values = numpy.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return columns, values
