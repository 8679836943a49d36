# Installs the built project into a scratch prefix, then configures, builds and runs a consumer
# project that uses find_package(dnurbs); then builds the same consumer with the compiler alone
# and the flags of pkg-config's dnurbs.pc, from a copy of the prefix moved elsewhere (the .pc
# file finds its prefix relative to itself), and runs it, and compiles every installed header with
# that include folder alone. Run by ctest with -DBINARY_DIR and
# -DSOURCE_DIR.
set(prefix "${BINARY_DIR}/install-check/prefix")
set(consumer_build "${BINARY_DIR}/install-check/consumer")
file(REMOVE_RECURSE "${BINARY_DIR}/install-check")
# Runs a command; a non-zero exit fails the check with the command and its output.
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "step failed (${result}): ${ARGN}\n${output}")
  endif()
endfunction()
run_step(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${prefix})
run_step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${consumer_build}
         -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run_step(${CMAKE_COMMAND} --build ${consumer_build})
run_step(${consumer_build}/consumer)

# pkg-config, from a moved copy of the prefix
set(moved "${BINARY_DIR}/install-check/moved")
file(COPY "${prefix}/" DESTINATION "${moved}")
file(GLOB_RECURSE pc_files "${moved}/*/dnurbs.pc")
list(LENGTH pc_files pc_count)
if(NOT pc_count EQUAL 1)
  message(FATAL_ERROR "expected one installed dnurbs.pc under ${moved}, found: ${pc_files}")
endif()
get_filename_component(pc_folder "${pc_files}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pc_folder}")
execute_process(COMMAND pkg-config --cflags --libs dnurbs RESULT_VARIABLE result
                OUTPUT_VARIABLE flags ERROR_VARIABLE error OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs dnurbs failed (${result}): ${error}")
endif()
execute_process(COMMAND pkg-config --variable=includedir dnurbs OUTPUT_VARIABLE include_folder
                OUTPUT_STRIP_TRAILING_WHITESPACE)
file(REAL_PATH "${include_folder}" include_folder)
file(REAL_PATH "${moved}/include" expected_folder)
if(NOT include_folder STREQUAL expected_folder)
  message(FATAL_ERROR "pkg-config's include folder ${include_folder} is not the moved prefix's")
endif()
separate_arguments(flag_list UNIX_COMMAND "${flags}")
set(pc_consumer "${BINARY_DIR}/install-check/pc_consumer")
run_step(c++ ${SOURCE_DIR}/tests/install/consumer/main.cpp -o ${pc_consumer} ${flag_list})
run_step(${pc_consumer})

# Every installed header compiles with the installed include folder alone and the compile flags
# of dnurbs.pc, named as a user names it ("dnurbs/io/scene.h"): one translation unit includes
# them all, so a header that includes another without the prefix fails here.
execute_process(COMMAND pkg-config --cflags dnurbs OUTPUT_VARIABLE cflags
                OUTPUT_STRIP_TRAILING_WHITESPACE)
separate_arguments(cflag_list UNIX_COMMAND "${cflags}")
file(GLOB_RECURSE headers RELATIVE "${moved}/include" "${moved}/include/dnurbs/*.h")
list(LENGTH headers header_count)
if(header_count LESS 100)
  message(FATAL_ERROR "expected the library's headers under ${moved}/include/dnurbs, found "
                      "${header_count}")
endif()
set(all_headers "${BINARY_DIR}/install-check/all_headers.cpp")
set(text "")
foreach(header IN LISTS headers)
  string(APPEND text "#include \"${header}\"\n")
endforeach()
file(WRITE "${all_headers}" "${text}")
run_step(c++ -fsyntax-only ${all_headers} ${cflag_list})
message(STATUS "installed dnurbs found and used by a consumer project, with CMake and with "
               "pkg-config; its ${header_count} headers compile from the installed include folder")
