# Runs one example small and checks what it wrote (cmake -P; see examples/CMakeLists.txt):
#   -DEXAMPLE=<program> -DOUTPUT=<directory> -DCOUNT=<frames or steps>
#   -DPATTERN=<glob of the OBJ files> -DFILES=<how many match>
#   -DVERTICES=<"v " lines per file> -DFACES=<"f " lines per file> [-DLINES=<"l " lines per file>]
#   (each a count N, or LOW..HIGH for a range: assimp's OBJ writer merges vertices at the same
#   position, so meshes that touch may share some)
#   [-DEXPECT=<regular expression the example's standard output must match>]
# Fails unless the example exits with 0, prints what EXPECT asks, and writes exactly FILES files
# matching PATTERN into OUTPUT, each with VERTICES vertices, FACES faces and LINES polylines
# (0 unless given).

foreach(variable EXAMPLE OUTPUT COUNT PATTERN FILES VERTICES FACES)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "check_example_output.cmake: -D${variable}=... is required")
  endif()
endforeach()
if(NOT DEFINED LINES)
  set(LINES 0)
endif()

file(REMOVE_RECURSE "${OUTPUT}")
execute_process(COMMAND "${EXAMPLE}" "${OUTPUT}" "${COUNT}" RESULT_VARIABLE status
                OUTPUT_VARIABLE standard_output ERROR_VARIABLE standard_error)
message(STATUS "${EXAMPLE} ${OUTPUT} ${COUNT}:\n${standard_output}${standard_error}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${EXAMPLE} exited with '${status}', expected 0")
endif()
if(DEFINED EXPECT AND NOT standard_output MATCHES "${EXPECT}")
  message(FATAL_ERROR "the output does not match the regular expression '${EXPECT}'")
endif()

file(GLOB written "${OUTPUT}/${PATTERN}")
list(LENGTH written written_count)
if(NOT written_count EQUAL FILES)
  message(FATAL_ERROR "${written_count} files match ${OUTPUT}/${PATTERN}, expected ${FILES}")
endif()
foreach(path IN LISTS written)
  foreach(kind v f l)
    file(STRINGS "${path}" records REGEX "^${kind} ")
    list(LENGTH records count)
    if(kind STREQUAL "v")
      set(expected ${VERTICES})
    elseif(kind STREQUAL "f")
      set(expected ${FACES})
    else()
      set(expected ${LINES})
    endif()
    if(expected MATCHES "^([0-9]+)\\.\\.([0-9]+)$")
      set(low ${CMAKE_MATCH_1})
      set(high ${CMAKE_MATCH_2})
    else()
      set(low ${expected})
      set(high ${expected})
    endif()
    if(count LESS low OR count GREATER high)
      message(FATAL_ERROR "${path} has ${count} '${kind} ' lines, expected ${expected}")
    endif()
  endforeach()
endforeach()
