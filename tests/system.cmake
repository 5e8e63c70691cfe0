if(NOT SM_WITH_TOP)
  return()
endif()
# Whole-IP tests (label system): the Verilated sm_top at the small configuration with
# stress timing, and at the paper configuration for the 30 frames/s budget.
function(sm_top_test name lib)
  add_executable(${name} ${CMAKE_SOURCE_DIR}/tests/tb_top.cpp)
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR}/sim ${CMAKE_SOURCE_DIR}/tests/common ${SM_GEN_DIR})
  target_link_libraries(${name} PRIVATE ${lib} sm_model sm_toolio sm_bench_options fmt::fmt ${OpenCV_LIBS})
endfunction()
sm_top_test(tb_top_small vtop_small)
sm_top_test(tb_top_small_fold vtop_small_fold)
sm_top_test(tb_top_paper vtop_paper)
sm_top_test(tb_top_zynq vtop_zynq)
sm_top_test(tb_top_vga vtop_vga)

set(_w ${CMAKE_BINARY_DIR}/waves)
file(MAKE_DIRECTORY ${_w})
add_test(NAME system_small_stress COMMAND tb_top_small --scene ${SM_SCENE_SMALL_DIR} --mode stress)
add_test(NAME system_small_vcd COMMAND tb_top_small --scene ${SM_SCENE_SMALL_DIR} --mode vcd --vcd ${_w}/system_small.vcd)
add_test(NAME system_small_budget COMMAND tb_top_small --scene ${SM_SCENE_SMALL_DIR} --mode budget)
# Calibration round trip: a small pair whose right camera is rotated and shifted; its
# calibration registers (rectifier grids) go over AXI4-Lite before the frame.
set(_rot ${CMAKE_BINARY_DIR}/scene_small_rot)
add_custom_command(OUTPUT ${_rot}/calib.json ${_rot}/left.png ${_rot}/right.png
  COMMAND sm_scene --width 64 --height 48 --levels 16 --seed 3 --objects 3 --rot-deg 1.5 --vshift 1.5 --out ${_rot}
  DEPENDS sm_scene COMMENT "Generating a distorted small stereo scene")
add_custom_target(sm_scene_small_rot ALL DEPENDS ${_rot}/calib.json)
add_test(NAME system_small_calib COMMAND tb_top_small --scene ${_rot} --mode calib --calib ${_rot}/calib.json)
add_test(NAME system_paper_budget COMMAND tb_top_paper --scene ${SM_SCENE_DIR} --mode budget)
# The folded datapath (PU < DISP): the small configuration at 4 clocks per pixel under
# stress and at camera timing (plus a continuous camera faster than the core, held by
# tready), and the zynq configuration's budget: the built-in scene at 30 frames/s camera
# timing on a 100 MHz core clock.
add_test(NAME system_small_fold_stress COMMAND tb_top_small_fold --scene ${SM_SCENE_SMALL_DIR} --mode stress)
add_test(NAME system_small_fold_budget COMMAND tb_top_small_fold --scene ${SM_SCENE_SMALL_DIR} --mode budget)
add_test(NAME system_zynq_budget COMMAND tb_top_zynq --scene ${SM_SCENE_DIR} --mode budget --mhz 100)
# The vga configuration (the zynq one at 640x480): one frame of a 640x480 scene at 30
# frames/s camera timing, on the slowest core clock the pacing rule allows (16 x the
# camera's pixel clock).
add_test(NAME system_vga_frame COMMAND tb_top_vga --scene ${SM_SCENE_VGA_DIR} --mode frame)
# A lost object packet: the object stream held until frame 2's output, so frame 1's list
# is published while frame 0's packet still waits (sm_objects' pkt_lost).
add_test(NAME system_small_lost COMMAND tb_top_small --scene ${SM_SCENE_SMALL_DIR} --mode lost)
add_test(NAME system_small_fold_lost COMMAND tb_top_small_fold --scene ${SM_SCENE_SMALL_DIR} --mode lost)
set_tests_properties(system_small_stress system_small_vcd system_small_budget system_small_calib
                     system_small_fold_stress system_small_fold_budget system_small_lost system_small_fold_lost
                     PROPERTIES LABELS "system" TIMEOUT 600)
set_tests_properties(system_paper_budget system_zynq_budget system_vga_frame PROPERTIES LABELS "system;slow"
                     TIMEOUT 1800)

# stereo_sim's input modes (--left/--right, --sequence, --video) and their errors, on the
# small configuration (each run checks the RTL against the model itself).
sm_unit_test(test_sim_inputs TEST system_sim_inputs LIBS sm_toolio nlohmann_json::nlohmann_json ${OpenCV_LIBS}
             INCLUDES ${CMAKE_SOURCE_DIR}/tests/common
             DEFINES SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_inputs_tmp"
                     SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>"
             DEPENDS stereo_sim_small LABELS system TIMEOUT 600)

# Frame-parallel runs (issue 41): a 12-frame sequence with a register schedule across the
# shard boundary through stereo_sim --jobs 2 gives the serial run's per-frame results and
# disparity files; a failing shard leaves no merged output (tests/sim_shards_check.py).
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  add_test(NAME system_sim_jobs
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/tests/sim_shards_check.py --mode jobs
                   --stereo-sim $<TARGET_FILE:stereo_sim_small> --sm-scene $<TARGET_FILE:sm_scene>
                   --tmp ${CMAKE_CURRENT_BINARY_DIR}/sim_jobs_tmp)
  set_tests_properties(system_sim_jobs PROPERTIES LABELS "system" TIMEOUT 300)
endif()
