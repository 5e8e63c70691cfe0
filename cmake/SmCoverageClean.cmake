# cmake -DDATA_DIR=<coverage dir> -DTEST_NAME=<test name> -P SmCoverageClean.cmake
# The setup fixture of every test of a coverage build (tests/CMakeLists.txt): removes the
# test's data files of an earlier run, <test>.dat and <test>.<n>.dat. A test writes the
# first free name of these (tests/common/sm_coverage.hpp), so without this a re-run would
# add its data beside the old run's, and coverage_report would merge both: points of the
# RTL as it was then, counted again at their old lines.
foreach(v DATA_DIR TEST_NAME)
  if(NOT ${v})
    message(FATAL_ERROR "SmCoverageClean.cmake: ${v} not set")
  endif()
endforeach()
file(GLOB old "${DATA_DIR}/${TEST_NAME}.dat" "${DATA_DIR}/${TEST_NAME}.[0-9]*.dat")
if(old)
  file(REMOVE ${old})
endif()
