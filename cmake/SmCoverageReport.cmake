# cmake -DDATA_DIR=... -DOUT_DIR=... -DVERILATOR_COVERAGE=... -DGENHTML=... (may be empty)
#       -DSM_COVERAGE_TOOL=... -P SmCoverageReport.cmake
# The coverage_report target (tools/coverage.cmake): merges every DATA_DIR/*.dat (one per
# test of the coverage build) with verilator_coverage, prints the per-module table of
# sm_coverage and writes OUT_DIR/coverage.json, the lcov reports OUT_DIR/html/line and
# OUT_DIR/html/toggle (genhtml of verilator_coverage --write-info of the line and toggle
# points apart) and the annotated sources OUT_DIR/annotated/{line,toggle}.
foreach(v DATA_DIR OUT_DIR VERILATOR_COVERAGE SM_COVERAGE_TOOL)
  if(NOT ${v})
    message(FATAL_ERROR "SmCoverageReport.cmake: ${v} not set")
  endif()
endforeach()
file(GLOB dats ${DATA_DIR}/*.dat)
if(NOT dats)
  message(FATAL_ERROR "no coverage data in ${DATA_DIR}: run ctest in the coverage build (-DSM_COVERAGE=ON) first")
endif()
list(LENGTH dats n)
message(STATUS "merging ${n} coverage files of ${DATA_DIR}")
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " cmd)
    message(FATAL_ERROR "failed (${rc}): ${cmd}")
  endif()
endfunction()

run(${VERILATOR_COVERAGE} --write ${OUT_DIR}/merged.dat ${dats})
run(${SM_COVERAGE_TOOL} ${OUT_DIR}/merged.dat --json ${OUT_DIR}/coverage.json --line-dat ${OUT_DIR}/line.dat
    --toggle-dat ${OUT_DIR}/toggle.dat)
execute_process(COMMAND ${SM_COVERAGE_TOOL} ${OUT_DIR}/merged.dat --markdown --list-uncovered
                OUTPUT_FILE ${OUT_DIR}/coverage.md RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "failed (${rc}): ${SM_COVERAGE_TOOL} --markdown")
endif()
foreach(kind line toggle)
  # verilator_coverage sums the points of one line and column (e.g. every bit of a bus) in
  # its lcov and annotated output; the table above counts every point on its own.
  if(kind STREQUAL "line")
    set(min 1)
  else()
    set(min 2)
  endif()
  run(${VERILATOR_COVERAGE} --write-info ${OUT_DIR}/${kind}.info ${OUT_DIR}/${kind}.dat)
  file(MAKE_DIRECTORY ${OUT_DIR}/annotated/${kind})
  run(${VERILATOR_COVERAGE} --annotate ${OUT_DIR}/annotated/${kind} --annotate-min ${min} ${OUT_DIR}/${kind}.dat)
  if(GENHTML)
    run(${GENHTML} --quiet --title "sm ${kind} coverage" --output-directory ${OUT_DIR}/html/${kind}
        ${OUT_DIR}/${kind}.info)
  endif()
endforeach()
message(STATUS "coverage report: ${OUT_DIR}/coverage.json, ${OUT_DIR}/coverage.md, ${OUT_DIR}/html/{line,toggle}/index.html, ${OUT_DIR}/annotated/{line,toggle}")
