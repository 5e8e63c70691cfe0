# Support-weight aggregation (docs/algorithm.md section 5): model unit tests and block tests.
add_executable(test_aggregate_model ${CMAKE_CURRENT_LIST_DIR}/test_aggregate_model.cpp)
target_link_libraries(test_aggregate_model PRIVATE sm_model Catch2::Catch2 ${OpenCV_LIBS})
target_include_directories(test_aggregate_model PRIVATE ${OpenCV_INCLUDE_DIRS})
target_compile_options(test_aggregate_model PRIVATE ${SM_WARNINGS})
catch_discover_tests(test_aggregate_model PROPERTIES LABELS unit)

# Block tests: odd width 37, three frames back to back, 30 % idle cycles.
set(_agg_tb ${CMAKE_CURRENT_LIST_DIR}/tb_sw_aggregate.cpp)
sm_rtl_test(NAME tb_sw_aggregate_sw3 TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 SW=3 COST_SHIFT=2
            ARGS --width 37 --heights 9 6 11)
sm_rtl_test(NAME tb_sw_aggregate_sw5 TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 SW=5 COST_SHIFT=1
            ARGS --width 37 --heights 9 4 11 --seed 2)
sm_rtl_test(NAME tb_sw_aggregate_paper TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=320 DISP=128 CENSUS=15 SW=5 COST_SHIFT=2
            ARGS --width 317 --heights 6 5 --seed 3 LABELS "rtl;slow")
foreach(_t tb_sw_aggregate_sw3 tb_sw_aggregate_sw5 tb_sw_aggregate_paper)
  target_link_libraries(${_t} PRIVATE CLI11::CLI11)
endforeach()
# Full MAX_WIDTH line (last column of the line buffer) with the paper-point binary.
add_test(NAME tb_sw_aggregate_paper_w320
         COMMAND tb_sw_aggregate_paper --width 320 --heights 7 6 --seed 4 --idle 50)
set_tests_properties(tb_sw_aggregate_paper_w320 PROPERTIES LABELS "rtl;slow" TIMEOUT 600)
