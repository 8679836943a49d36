# dnurbs_add_library(<folder> DEPENDS <targets...>)
# Builds the library dnurbs_<folder> (alias dnurbs::<folder>) from <folder>/**/*.cpp (sub-folders
# included); a folder with
# no sources yet becomes an interface library. Headers are included as "dnurbs/<folder>/x.h":
# in the build tree through DNURBS_INCLUDE_ROOT (CMakeLists.txt), installed under
# include/dnurbs/<folder>.
function(dnurbs_add_library folder)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/${folder}/*.cpp")
  set(target dnurbs_${folder})
  if(sources)
    add_library(${target} ${sources})
    target_link_libraries(${target} PUBLIC ${ARG_DEPENDS} PRIVATE dnurbs_warnings)
    target_compile_features(${target} PUBLIC cxx_std_20)
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${DNURBS_INCLUDE_ROOT}>
                               $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${folder} POSITION_INDEPENDENT_CODE ON)
    # The standard and Eigen headers nearly every file includes, compiled once per library
    # rather than once per file. clang-tidy reads each file without it
    # (scripts/clang_tidy_check.sh), which also checks that every file includes what it uses.
    target_precompile_headers(${target} PRIVATE <Eigen/Core> <Eigen/Sparse> <algorithm> <array>
                              <cmath> <functional> <memory> <optional> <string> <vector>)
  else()
    add_library(${target} INTERFACE)
    target_link_libraries(${target} INTERFACE ${ARG_DEPENDS})
    target_compile_features(${target} INTERFACE cxx_std_20)
    target_include_directories(${target} INTERFACE $<BUILD_INTERFACE:${DNURBS_INCLUDE_ROOT}>
                               $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${folder})
  endif()
  add_library(dnurbs::${folder} ALIAS ${target})
  install(TARGETS ${target} EXPORT dnurbsTargets)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/${folder}/" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dnurbs/${folder}
          FILES_MATCHING PATTERN "*.h")
endfunction()

# dnurbs_test_settings(<target>): what every test executable and the test precompiled header
# share, so that the header compiled once is valid for each of them (the same options and
# definitions; clang refuses a header whose macros differ). The tests' own code (set-up and
# checks) is compiled at -O1 in Release builds with the standard, gtest and Eigen headers
# precompiled: the library under test keeps -O3, and the suite, the largest part of what CI
# compiles, builds in about half the CPU time (tests/nurbs and tests/io: 256 s at -O3, 134 s at
# -O1 with the precompiled headers). Without -ffast-math the floating-point results do not
# depend on the level. At -O1 g++ 12 reports maybe-uninitialized inside Eigen's DenseStorage
# move (a false positive its -O3 inlining removes), so that warning is off for the tests only.
function(dnurbs_test_settings target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-O1>
                         $<$<AND:$<CONFIG:Release>,$<CXX_COMPILER_ID:GNU>>:-Wno-maybe-uninitialized>)
  target_link_libraries(${target} PRIVATE GTest::gtest_main GTest::gmock dnurbs_warnings)
  target_compile_definitions(${target} PRIVATE
                             DNURBS_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data"
                             DNURBS_BINARY_DIR="${PROJECT_BINARY_DIR}")
endfunction()

# dnurbs_test_pch(): the object library dnurbs_test_pch (made once) that owns the tests'
# precompiled header.
function(dnurbs_test_pch)
  if(TARGET dnurbs_test_pch)
    return()
  endif()
  set(source "${PROJECT_BINARY_DIR}/dnurbs_test_pch.cpp")
  file(WRITE "${source}" "// The translation unit that owns the tests' precompiled header\n")
  add_library(dnurbs_test_pch OBJECT "${source}")
  target_compile_features(dnurbs_test_pch PRIVATE cxx_std_20)
  target_link_libraries(dnurbs_test_pch PRIVATE Eigen3::Eigen)
  dnurbs_test_settings(dnurbs_test_pch)
  target_precompile_headers(dnurbs_test_pch PRIVATE <gtest/gtest.h> <gmock/gmock.h> <Eigen/Dense>
                            <Eigen/Sparse> <algorithm> <cmath> <filesystem> <fstream> <iostream>
                            <limits> <random> <string> <vector>)
endfunction()

# dnurbs_add_test_folder(<folder> [LABELS <labels...>] [DEPENDS <targets...>]
#                        [SOURCES <files of tests/common...>])
# One GoogleTest executable test_<folder> (slashes become underscores) from tests/<folder>/*.cpp,
# the tests of the library folder of the same path (tests/dynamics/grid/test_snake.cpp for
# dynamics/grid/snake.cpp); one ctest test per test case, labelled with the folder's first path
# component and any extra labels. It links the library of that first component only, so that a
# broken upper layer cannot hide a lower one. SOURCES adds shared test sources (tests/common).
function(dnurbs_add_test_folder folder)
  cmake_parse_arguments(ARG "" "" "LABELS;DEPENDS;SOURCES" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${folder}/*.cpp")
  if(NOT sources)
    return()
  endif()
  string(REPLACE "/" "_" name "${folder}")
  string(REGEX REPLACE "/.*" "" layer "${folder}")
  list(TRANSFORM ARG_SOURCES PREPEND "${CMAKE_CURRENT_SOURCE_DIR}/common/")
  add_executable(test_${name} ${sources} ${ARG_SOURCES})
  dnurbs_test_settings(test_${name})
  # Every test executable reuses the one precompiled header of dnurbs_test_pch (one 13 s
  # compile instead of one per executable: 18 of them when the suite was split by folder)
  dnurbs_test_pch()
  target_precompile_headers(test_${name} REUSE_FROM dnurbs_test_pch)
  if(TARGET dnurbs::${layer})
    set(library dnurbs::${layer})
  else()
    set(library dnurbs::dnurbs)
  endif()
  target_link_libraries(test_${name} PRIVATE ${library} ${ARG_DEPENDS})
  gtest_discover_tests(test_${name} PROPERTIES LABELS ${layer} DISCOVERY_TIMEOUT 60
                       TEST_LIST test_${name}_TESTS)
  if(ARG_LABELS)
    # gtest_discover_tests splits a list-valued LABELS property, so extra labels are set by a
    # script that ctest runs after the discovered tests are defined.
    set(labels "${layer};${ARG_LABELS}")
    set(script "${CMAKE_CURRENT_BINARY_DIR}/test_${name}_labels.cmake")
    file(WRITE "${script}"
         "foreach(test IN LISTS test_${name}_TESTS)\n"
         "  set_tests_properties(\"\${test}\" PROPERTIES LABELS \"${labels}\")\n"
         "endforeach()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${script}")
  endif()
endfunction()
