# sm_calibrate's and sm_float_ref's bad inputs and outputs (label robust, docs/robustness.md
# "The tools"): exit code, the one error line, no output left. Inputs made by the test (a
# synthetic chessboard rig, a small scene); no ../shared, no Verilated model.
if(TARGET sm_calibrate AND TARGET sm_float_ref_tool AND TARGET sm_toolio)
  sm_unit_test(test_calib_float_robust LIBS sm_float_ref sm_toolio INCLUDES ${CMAKE_CURRENT_LIST_DIR}/common
               DEFINES SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tools_tmp/test_calib_float_robust"
               SM_CALIBRATE_EXE="$<TARGET_FILE:sm_calibrate>" SM_FLOAT_REF_EXE="$<TARGET_FILE:sm_float_ref_tool>"
               DEPENDS sm_calibrate sm_float_ref_tool LABELS robust)
endif()
if(NOT SM_WITH_TOP)
  return()
endif()
# Robustness of the integrated IP (label robust): a fixed-seed randomized mix of
# well-formed frames, stream faults and register faults through the Verilated sm_top at
# the small configuration (docs/robustness.md). The Verilated library is built with
# --assert, so the RTL's internal assertions are live.
set_source_files_properties(${CMAKE_SOURCE_DIR}/tests/tb_faults.cpp
                            PROPERTIES COMPILE_OPTIONS "${SM_WARNINGS}")
foreach(v "tb_faults;vtop_small" "tb_faults_fold;vtop_small_fold")
  list(GET v 0 exe)
  list(GET v 1 lib)
  add_executable(${exe} ${CMAKE_SOURCE_DIR}/tests/tb_faults.cpp)
  target_include_directories(${exe} PRIVATE ${CMAKE_SOURCE_DIR}/sim ${CMAKE_SOURCE_DIR}/tests/common ${SM_GEN_DIR})
  target_link_libraries(${exe} PRIVATE ${lib} sm_model sm_toolio sm_bench_options fmt::fmt ${OpenCV_LIBS})
endforeach()
# The main run: ~1000 input steps mixing every fault class (a few seconds).
add_test(NAME robust_faults COMMAND tb_faults --scene ${SM_SCENE_SMALL_DIR} --steps 1000 --seed 20240611
                                            --no-soft-reset)
# A second seed: different fault positions.
add_test(NAME robust_faults_seed2 COMMAND tb_faults --scene ${SM_SCENE_SMALL_DIR} --steps 400 --seed 7 --no-soft-reset)
# Same mix plus CONTROL.SOFT_RESET mid-frame. Fails while rtl/sm_top.v declares rst_n
# twice (line 80 `wire rst_n = aresetn;` wins in Verilator, so the soft reset never
# reaches the sequencer, the pipeline or the output formatter).
add_test(NAME robust_faults_soft_reset COMMAND tb_faults --scene ${SM_SCENE_SMALL_DIR} --steps 400 --seed 11)
# The folded small configuration (4 clocks per pixel): a fault or a soft reset while a
# pixel is half-way through its clocks recovers like any other.
add_test(NAME robust_faults_fold COMMAND tb_faults_fold --scene ${SM_SCENE_SMALL_DIR} --steps 400 --seed 5)
# aresetn of 1, 2 and 3 clocks at every phase (frame start, a pixel without tuser,
# mid-frame, the frame's tail, the object list's publish -2..0 clocks, the object packet
# mid-send, an AXI4-Lite write / soft-reset write / read in flight, a full input FIFO):
# the state after must equal the state after a 16-clock reset at the same point, and the
# documented reset state (issue 40). Both configurations: the folded one paces the
# pipeline, so its phases fall elsewhere.
add_test(NAME robust_reset_phases COMMAND tb_faults --scene ${SM_SCENE_SMALL_DIR} --reset-phases)
add_test(NAME robust_reset_phases_fold COMMAND tb_faults_fold --scene ${SM_SCENE_SMALL_DIR} --reset-phases)
set_tests_properties(robust_faults robust_faults_seed2 robust_faults_soft_reset robust_faults_fold
                     robust_reset_phases robust_reset_phases_fold PROPERTIES LABELS "robust" TIMEOUT 900)
