# Installs the built project into a scratch prefix, then configures, builds and runs a consumer
# project that uses find_package(dnurbs). Run by ctest with -DBINARY_DIR and -DSOURCE_DIR.
set(prefix "${BINARY_DIR}/install-check/prefix")
set(consumer_build "${BINARY_DIR}/install-check/consumer")
file(REMOVE_RECURSE "${BINARY_DIR}/install-check")
foreach(step
    "${CMAKE_COMMAND};--install;${BINARY_DIR};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/tests/install/consumer;-B;${consumer_build};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${consumer_build}"
    "${consumer_build}/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "step failed (${result}): ${step}\n${output}")
  endif()
endforeach()
message(STATUS "installed dnurbs found and used by a consumer project")
