# Finds what the dnurbs Python module (python/) needs: a Python 3 interpreter that has NumPy,
# its development headers (Development.Module) and pybind11 (Debian's pybind11-dev ships a
# CMake package config). Sets DNURBS_PYTHON_FOUND, the default of DNURBS_BUILD_PYTHON.
#
# The interpreter: Python3_EXECUTABLE if given, else the first of `python3` on PATH and Debian's
# /usr/bin/python3 that imports numpy (a python3 on PATH from pyenv or a virtual environment
# without NumPy would build a module its tests cannot import).
set(DNURBS_PYTHON_FOUND OFF)
if(NOT DEFINED Python3_EXECUTABLE AND NOT DEFINED CACHE{Python3_EXECUTABLE})
  find_program(dnurbs_path_python3 NAMES python3 NO_CACHE)
  foreach(candidate IN ITEMS "${dnurbs_path_python3}" /usr/bin/python3)
    if(candidate AND EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import numpy" RESULT_VARIABLE has_numpy
                      OUTPUT_QUIET ERROR_QUIET)
      if(has_numpy EQUAL 0)
        set(Python3_EXECUTABLE "${candidate}" CACHE FILEPATH "Python interpreter of the dnurbs module")
        break()
      endif()
    endif()
  endforeach()
endif()
find_package(Python3 3.8 COMPONENTS Interpreter Development.Module QUIET)
find_package(pybind11 2.6 CONFIG QUIET)
if(Python3_FOUND AND pybind11_FOUND)
  execute_process(COMMAND "${Python3_EXECUTABLE}" -c "import numpy" RESULT_VARIABLE has_numpy
                  OUTPUT_QUIET ERROR_QUIET)
  if(has_numpy EQUAL 0)
    set(DNURBS_PYTHON_FOUND ON)
  endif()
endif()
if(NOT DNURBS_PYTHON_FOUND)
  message(STATUS "dnurbs: no Python module (needs Python 3 with NumPy and its headers, and "
                 "pybind11: Debian's python3-dev python3-numpy pybind11-dev)")
endif()
