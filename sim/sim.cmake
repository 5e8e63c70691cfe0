if(NOT SM_WITH_TOP)
  return()
endif()
# stereo_sim: the Verilated IP at a configuration plus the harness. The paper
# configuration is the main target; a small one serves the fast system tests.
set(SM_SIM_THREADS 1 CACHE STRING "Verilator threads of the stereo_sim model")

# sm_add_sim(<target> <params...>)
function(sm_add_sim target)
  add_executable(${target} ${CMAKE_CURRENT_SOURCE_DIR}/stereo_sim.cpp)
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${SM_GEN_DIR})
  target_link_libraries(${target} PRIVATE sm_model sm_toolio fmt::fmt CLI11::CLI11
                                          nlohmann_json::nlohmann_json ${OpenCV_LIBS})
  string(REPLACE ";" "_" cfg "${ARGN}")
  target_compile_definitions(${target} PRIVATE
    SM_DEFAULT_SCENE="${CMAKE_BINARY_DIR}/scene"
    SM_SYNTH_JSON="${CMAKE_BINARY_DIR}/synth/sm_top_${target}.json")
  sm_verilated(TARGET ${target} TOP sm_top PARAMS ${ARGN} TRACE THREADS ${SM_SIM_THREADS})
  add_dependencies(${target} sm_regmap_gen_files)
endfunction()
sm_add_sim(stereo_sim ${SM_PAPER_PARAMS})
sm_add_sim(stereo_sim_small ${SM_SMALL_PARAMS})
