# FindCHOLMOD
# Finds CHOLMOD (SuiteSparse's sparse Cholesky). Debian 12 ships SuiteSparse 5.12 (package
# libsuitesparse-dev) without a CMake package config (those arrive with SuiteSparse 7), so this
# module looks for the header and the shared library itself.
#
# Defines the imported target CHOLMOD::CHOLMOD and CHOLMOD_FOUND, CHOLMOD_INCLUDE_DIR,
# CHOLMOD_LIBRARY, CHOLMOD_VERSION. The shared libcholmod brings its own dependencies
# (SuiteSparse_config, AMD, CAMD, COLAMD, CCOLAMD, METIS, BLAS, LAPACK) at run time; BLAS and LAPACK
# are whichever libblas.so.3 / liblapack.so.3 Debian's alternatives point to (OpenBLAS once
# libopenblas-dev is installed).
include(FindPackageHandleStandardArgs)

find_path(CHOLMOD_INCLUDE_DIR NAMES cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY NAMES cholmod)

if(CHOLMOD_INCLUDE_DIR AND EXISTS "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h")
  file(STRINGS "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h" version_lines
       REGEX "^#define CHOLMOD_(MAIN|SUB|SUBSUB)_VERSION[ \t]+[0-9]+")
  foreach(part MAIN SUB SUBSUB)
    string(REGEX MATCH "CHOLMOD_${part}_VERSION[ \t]+([0-9]+)" _ "${version_lines}")
    set(CHOLMOD_${part} "${CMAKE_MATCH_1}")
  endforeach()
  set(CHOLMOD_VERSION "${CHOLMOD_MAIN}.${CHOLMOD_SUB}.${CHOLMOD_SUBSUB}")
endif()

find_package_handle_standard_args(CHOLMOD REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR
                                  VERSION_VAR CHOLMOD_VERSION)

if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY)
