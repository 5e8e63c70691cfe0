# Coverage (docs/verification.md, "Coverage"): sm_coverage, the per-module line and toggle
# table of Verilator coverage data (always built: the unit test coverage_tool checks it),
# and with -DSM_COVERAGE=ON the target coverage_report, which merges the data every test
# of the coverage build wrote (<build>/coverage/*.dat) into <build>/coverage_report/:
# merged.dat, coverage.json, the lcov reports html/line and html/toggle, annotated/.
add_executable(sm_coverage ${CMAKE_CURRENT_SOURCE_DIR}/sm_coverage.cpp)
target_link_libraries(sm_coverage PRIVATE fmt::fmt CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(sm_coverage PRIVATE ${SM_WARNINGS})
# toolio/sm_cli.hpp (and sm_json_file.hpp): header-only, no link to sm_toolio
target_include_directories(sm_coverage PRIVATE ${CMAKE_SOURCE_DIR})

if(SM_COVERAGE)
  find_program(SM_VERILATOR_COVERAGE verilator_coverage HINTS ${VERILATOR_ROOT}/bin /usr/bin REQUIRED)
  find_program(SM_GENHTML genhtml)
  if(NOT SM_GENHTML)
    message(WARNING "genhtml not found (Debian package lcov, scripts/deps.sh): coverage_report writes no HTML")
    set(SM_GENHTML "")
  endif()
  add_custom_target(coverage_report
    COMMAND ${CMAKE_COMMAND} -DDATA_DIR=${CMAKE_BINARY_DIR}/coverage -DOUT_DIR=${CMAKE_BINARY_DIR}/coverage_report
            -DVERILATOR_COVERAGE=${SM_VERILATOR_COVERAGE} -DGENHTML=${SM_GENHTML}
            -DSM_COVERAGE_TOOL=$<TARGET_FILE:sm_coverage>
            -P ${CMAKE_SOURCE_DIR}/cmake/SmCoverageReport.cmake
    DEPENDS sm_coverage USES_TERMINAL
    COMMENT "Coverage report of the data in ${CMAKE_BINARY_DIR}/coverage")
endif()
