if(NOT SM_WITH_TOP)
  return()
endif()
# The Verilated IP, once per configuration, as a static library that stereo_sim and the
# system tests share (the paper configuration is ~150 MB of generated C++).
set(SM_SIM_THREADS 1 CACHE STRING "Verilator threads of the stereo_sim model")
# Extra compiler flags for the per-cycle code of the Verilated tops (stereo_sim, the
# system tests), e.g. -march=native for a benchmark build (docs/performance.md).
set(SM_SIM_CXXFLAGS "" CACHE STRING "Extra compiler flags of the Verilated tops' per-cycle code")
separate_arguments(_sm_sim_cxxflags UNIX_COMMAND "${SM_SIM_CXXFLAGS}")

# sm_vtop(<library> <params...>): sm_top verilated at a configuration, with tracing of
# sm_top's ports and inter-stage wires (depth 1: a full-depth trace of the paper
# configuration is ~0.5 MB per cycle). Depth 2 would add every signal inside the
# blocks, and Verilator must then keep each traced wire as a variable updated every
# clock, even with no trace open: at the paper configuration that cost a fifth of the
# simulation time (wide internal vectors copied or assembled bit by bit).
function(sm_vtop lib)
  add_library(${lib} STATIC ${CMAKE_SOURCE_DIR}/sim/sm_vtop_anchor.cpp)
  # The run-once code (construction, initial blocks, trace declarations: about half of
  # the generated C++) is built at -O1, which saves compile time and no run time.
  sm_verilated(TARGET ${lib} TOP sm_top PARAMS ${ARGN} TRACE TRACE_DEPTH 1 THREADS ${SM_SIM_THREADS}
               OPT_SLOW -O1 OPT_FAST ${_sm_sim_cxxflags})
  add_dependencies(${lib} sm_regmap_gen_files)
  get_target_property(defs ${lib} COMPILE_DEFINITIONS)
  # The copy taken here still has verilate()'s tracing-off defaults: the harness must see
  # the library's real VM_TRACE to open VCDs.
  list(FILTER defs EXCLUDE REGEX "^VM_TRACE")
  target_compile_definitions(${lib} INTERFACE ${defs} VM_TRACE=1 VM_TRACE_VCD=1 VM_TRACE_FST=0)
  get_target_property(incs ${lib} INCLUDE_DIRECTORIES)
  target_include_directories(${lib} INTERFACE ${incs})
endfunction()
sm_vtop(vtop_paper ${SM_PAPER_PARAMS})
sm_vtop(vtop_small ${SM_SMALL_PARAMS})

# sm_add_sim(<target> <vtop library>)
function(sm_add_sim target lib)
  add_executable(${target} ${CMAKE_CURRENT_SOURCE_DIR}/stereo_sim.cpp)
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${SM_GEN_DIR})
  target_link_libraries(${target} PRIVATE ${lib} sm_model sm_toolio fmt::fmt CLI11::CLI11
                                          nlohmann_json::nlohmann_json ${OpenCV_LIBS})
  target_compile_definitions(${target} PRIVATE
    SM_DEFAULT_SCENE="${CMAKE_BINARY_DIR}/scene"
    SM_SYNTH_JSON="${CMAKE_BINARY_DIR}/synth/sm_top_${target}.json"
    SM_SYNTH_JSON_DOCS="${CMAKE_SOURCE_DIR}/docs/synth/sm_top_${target}.json")
  # the default input: building stereo_sim alone must leave it runnable
  add_dependencies(${target} sm_default_scene)
endfunction()
sm_add_sim(stereo_sim vtop_paper)
sm_add_sim(stereo_sim_small vtop_small)
