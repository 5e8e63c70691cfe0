if(NOT SM_WITH_TOP)
  return()
endif()
# Whole-IP tests (label system): the Verilated sm_top at the small configuration with
# stress timing, and at the paper configuration for the 30 frames/s budget.
function(sm_top_test name params)
  add_executable(${name} ${CMAKE_SOURCE_DIR}/tests/tb_top.cpp)
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR}/sim ${CMAKE_SOURCE_DIR}/tests/common ${SM_GEN_DIR})
  target_link_libraries(${name} PRIVATE sm_model sm_toolio fmt::fmt ${OpenCV_LIBS})
  sm_verilated(TARGET ${name} TOP sm_top PARAMS ${params} TRACE)
  add_dependencies(${name} sm_regmap_gen_files)
endfunction()
sm_top_test(tb_top_small "${SM_SMALL_PARAMS}")
sm_top_test(tb_top_paper "${SM_PAPER_PARAMS}")

add_test(NAME system_small_stress COMMAND tb_top_small ${CMAKE_BINARY_DIR}/scene_small stress)
add_test(NAME system_small_vcd COMMAND tb_top_small ${CMAKE_BINARY_DIR}/scene_small vcd
                                       ${CMAKE_BINARY_DIR}/waves/system_small.vcd)
add_test(NAME system_paper_budget COMMAND tb_top_paper ${CMAKE_BINARY_DIR}/scene budget)
set_tests_properties(system_small_stress system_small_vcd PROPERTIES LABELS "system" TIMEOUT 600)
set_tests_properties(system_paper_budget PROPERTIES LABELS "system;slow" TIMEOUT 1800)
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/waves)
