# Installs the Python component of the built project into a scratch prefix (cmake --install
# --component python) and imports the installed module from there: the package lands in
# <prefix>/${DNURBS_PYTHON_INSTALL_DIR}/dnurbs and evaluates a sphere of radius 2. Run by ctest
# with -DBINARY_DIR, -DPYTHON and -DINSTALL_DIR.
set(prefix "${BINARY_DIR}/python-install-check")
file(REMOVE_RECURSE "${prefix}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --component python --prefix
                        "${prefix}" RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install --component python failed (${result}):\n${output}")
endif()
if(IS_ABSOLUTE "${INSTALL_DIR}")
  set(site "${INSTALL_DIR}")
else()
  set(site "${prefix}/${INSTALL_DIR}")
endif()
set(script "import dnurbs, numpy, pathlib; assert pathlib.Path(dnurbs.__file__).is_relative_to('${site}'), dnurbs.__file__; r = numpy.linalg.norm(dnurbs.sphere(2.0)(0.3, 0.4)); assert abs(r - 2.0) < 1e-14, r; print(dnurbs.__file__)")
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${site}" "${PYTHON}" -c "${script}"
                WORKING_DIRECTORY "${prefix}" RESULT_VARIABLE result OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the installed module does not import from ${site} (${result}):\n${output}")
endif()
message(STATUS "installed Python module: ${output}")
