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
# GCC profile-guided optimization of the same per-cycle code, in two builds of one build
# folder (bench/pgo_build.sh does both and the training run): GENERATE instruments it
# (the .gcda profiles land beside its object files when a binary linked with it exits),
# USE recompiles it with those profiles. Verilator's manual recommends this for speed
# ("Compiler Profile-Guided Optimization"); the RTL and every output bit stay the same.
set(SM_SIM_PGO OFF CACHE STRING "Profile-guided build of the Verilated tops' per-cycle code: OFF, GENERATE or USE")
set_property(CACHE SM_SIM_PGO PROPERTY STRINGS OFF GENERATE USE)
set(_sm_sim_pgo_link "")
if(SM_SIM_PGO STREQUAL "GENERATE" OR SM_SIM_PGO STREQUAL "USE")
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    message(FATAL_ERROR "SM_SIM_PGO=${SM_SIM_PGO} needs GCC (the compiler is ${CMAKE_CXX_COMPILER_ID})")
  endif()
  if(SM_SIM_PGO STREQUAL "GENERATE")
    # several model threads update the same counters
    if(SM_SIM_THREADS GREATER 1)
      list(APPEND _sm_sim_cxxflags -fprofile-generate -fprofile-update=prefer-atomic)
    else()
      list(APPEND _sm_sim_cxxflags -fprofile-generate)
    endif()
    set(_sm_sim_pgo_link -fprofile-generate)
  else()
    # Files without a profile (never run in training) are compiled as without PGO; a
    # profile from older generated code is a warning (the function is compiled without
    # it), not a failed build.
    list(APPEND _sm_sim_cxxflags -fprofile-use -fprofile-correction -Wno-missing-profile
         -Wno-error=coverage-mismatch)
  endif()
elseif(NOT SM_SIM_PGO STREQUAL "OFF")
  message(FATAL_ERROR "SM_SIM_PGO must be OFF, GENERATE or USE, not '${SM_SIM_PGO}'")
endif()

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
  if(_sm_sim_pgo_link)
    target_link_options(${lib} INTERFACE ${_sm_sim_pgo_link})
  endif()
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
