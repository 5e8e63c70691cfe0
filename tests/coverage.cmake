# sm_coverage (tools/sm_coverage.cpp) on two tiny coverage files with a known answer
# (tests/coverage/check_report.cmake): instances, two tests, the toggle threshold, a point
# of another kind, and bad input. The default build needs no coverage build for it.
add_test(NAME coverage_tool
         COMMAND ${CMAKE_COMMAND} -DTOOL=$<TARGET_FILE:sm_coverage> -DDATA=${CMAKE_CURRENT_LIST_DIR}/coverage
                 -DOUT=${CMAKE_CURRENT_BINARY_DIR}/coverage_tool_tmp -P ${CMAKE_CURRENT_LIST_DIR}/coverage/check_report.cmake)
set_tests_properties(coverage_tool PROPERTIES LABELS unit TIMEOUT 60)
