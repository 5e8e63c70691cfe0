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
# GCC at -O3 spends most of the per-cycle code's compile in alias queries and in global
# CSE / PRE over Verilator's long straight-line functions (-ftime-report on the paper
# configuration: alias walking 34 %, PRE 8 %, CSE after reload 11 %). Without GCSE and
# with fewer alias queries per access the paper model's per-cycle code compiles in 37 s of
# CPU instead of 61 s, and stereo_sim runs as fast (alternating whole-process runs, 5 each: paper 0.95,
# zynq 0.96 of the -O3 time). Before SM_SIM_CXXFLAGS, so a flag given there wins.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(PREPEND _sm_sim_cxxflags -fno-gcse -fno-gcse-after-reload
       --param=sccvn-max-alias-queries-per-access=100 --param=dse-max-alias-queries-per-store=32)
endif()
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
  # Four groups of per-cycle code: at -O3 the paper configuration's is the longest
  # compile of the build, and the groups keep both cores busy with it.
  sm_verilated(TARGET ${lib} TOP sm_top PARAMS ${ARGN} TRACE TRACE_DEPTH 1 THREADS ${SM_SIM_THREADS}
               FAST_GROUPS 4 OPT_FAST ${_sm_sim_cxxflags})
  if(_sm_sim_pgo_link)
    target_link_options(${lib} INTERFACE ${_sm_sim_pgo_link})
  endif()
endfunction()
sm_vtop(vtop_paper ${SM_PAPER_PARAMS})
sm_vtop(vtop_zynq ${SM_ZYNQ_PARAMS})
sm_vtop(vtop_vga ${SM_VGA_PARAMS})
sm_vtop(vtop_small ${SM_SMALL_PARAMS})
sm_vtop(vtop_small_fold ${SM_SMALL_FOLD_PARAMS})

# stereo_sim's configuration-independent part (sim/stereo_sim_app.hpp), compiled once
# for every stereo_sim_* executable. It sees no Verilated model (VM_TRACE=0: no trace
# header), only the harness's plain types.
# The run's stages, one file each (stereo_sim_app.cpp calls them in order).
add_library(sm_stereo_sim_app STATIC
  ${CMAKE_CURRENT_SOURCE_DIR}/stereo_sim_app.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_options.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_regplan.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_inputs.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_simulate.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_check.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_report.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_outputs.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_pictures.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_frame_source.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_shards.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_preflight.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_interrupt.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_depth.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/sm_sim_progress.cpp)
target_include_directories(sm_stereo_sim_app PUBLIC ${CMAKE_CURRENT_SOURCE_DIR} ${SM_GEN_DIR})
target_link_libraries(sm_stereo_sim_app PUBLIC sm_model sm_toolio sm_verilated fmt::fmt
                      PRIVATE CLI11::CLI11 nlohmann_json::nlohmann_json ${OpenCV_LIBS})
target_compile_definitions(sm_stereo_sim_app PRIVATE VM_TRACE=0 VM_COVERAGE=0)
# -O1 (compile time: 27 s at -O3): the per-cycle loop is in stereo_sim.cpp, the model
# check's reference model in sm_model, both at -O3
target_compile_options(sm_stereo_sim_app PRIVATE ${SM_WARNINGS} -O1)
add_dependencies(sm_stereo_sim_app sm_regmap_gen_files)

# sm_add_sim(<target> <vtop library> [<default scene folder>]): the default scene is one of
# the configuration's own size and disparity range (tools/scene.cmake), build/scene unless given.
function(sm_add_sim target lib)
  set(scene ${SM_SCENE_DIR})
  if(ARGC GREATER 2)
    set(scene ${ARGV2})
  endif()
  add_executable(${target} ${CMAKE_CURRENT_SOURCE_DIR}/stereo_sim.cpp)
  # tests/common: sm_coverage.hpp, so the tests that run stereo_sim count in the coverage
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${SM_GEN_DIR}
                                               ${CMAKE_SOURCE_DIR}/tests/common)
  target_link_libraries(${target} PRIVATE ${lib} sm_stereo_sim_app sm_model fmt::fmt)
  target_compile_options(${target} PRIVATE ${SM_WARNINGS})
  target_compile_definitions(${target} PRIVATE
    SM_DEFAULT_SCENE="${scene}"
    SM_SYNTH_JSON="${CMAKE_BINARY_DIR}/synth/sm_top_${target}.json"
    SM_SYNTH_JSON_DOCS="${CMAKE_SOURCE_DIR}/docs/synth/sm_top_${target}.json")
  # the default input: building stereo_sim alone must leave it runnable
  add_dependencies(${target} sm_default_scene)
endfunction()
sm_add_sim(stereo_sim vtop_paper)
sm_add_sim(stereo_sim_zynq vtop_zynq)
sm_add_sim(stereo_sim_vga vtop_vga ${SM_SCENE_VGA_DIR})
sm_add_sim(stereo_sim_small vtop_small ${SM_SCENE_SMALL_DIR})
sm_add_sim(stereo_sim_small_fold vtop_small_fold ${SM_SCENE_SMALL_DIR})

# Wave builds (issue 22): sm_top traced at full depth, so that one block's internals can
# be dumped at run time (stereo_sim --wave FILE.vcd|FILE.fst --wave-scope ... --wave-depth
# ...). The plain builds above stay at trace depth 1: a full-depth trace slows the model
# even with no trace open, so the wave builds are separate executables. Verilator 5.006
# writes one trace format per model (--trace or --trace-fst), so a wave library holds
# one model of the same RTL per format and stereo_sim picks the model by the file's
# extension. Their per-cycle code is built at -O1 (compile time; a debugging run needs no
# top speed). docs/verification.md, "Waves".
set(SM_WAVE_FORMATS "vcd;fst" CACHE STRING "Trace formats of the stereo_sim wave builds: vcd, fst or both")
option(SM_WAVE_PAPER "Build stereo_sim_wave (paper configuration, full-depth trace) with the default target" OFF)
function(sm_vtop_wave lib)
  add_library(${lib} STATIC ${CMAKE_SOURCE_DIR}/sim/sm_vtop_anchor.cpp)
  set(vargs)
  set(defs)
  sm_param_flags(vargs defs ${ARGN})
  set(n 0)
  foreach(fmt ${SM_WAVE_FORMATS})
    if(fmt STREQUAL "vcd")
      set(tr TRACE)
      list(APPEND defs SM_WAVE_VCD=V${lib}_vcd SM_WAVE_VCD_H="V${lib}_vcd.h")
    elseif(fmt STREQUAL "fst")
      set(tr TRACE_FST)
      list(APPEND defs SM_WAVE_FST=V${lib}_fst SM_WAVE_FST_H="V${lib}_fst.h")
    else()
      message(FATAL_ERROR "SM_WAVE_FORMATS: '${fmt}' is not vcd or fst")
    endif()
    sm_verilate_model(${lib} TOP sm_top PREFIX V${lib}_${fmt} VERILATOR_ARGS ${vargs} ${tr})
    math(EXPR n "${n} + 1")
  endforeach()
  if(n EQUAL 0)
    message(FATAL_ERROR "SM_WAVE_FORMATS is empty")
  endif()
  # a debugging run needs no top speed: the per-cycle code at -O1 (compile time)
  target_compile_options(${lib} PRIVATE -O1)
  target_compile_definitions(${lib} PUBLIC ${defs})
endfunction()

# sm_add_sim_wave(<target> <default scene folder> <params...>): stereo_sim on a wave library.
function(sm_add_sim_wave target scene)
  sm_vtop_wave(${target}_lib ${ARGN})
  sm_add_sim(${target} ${target}_lib ${scene})
  target_compile_definitions(${target} PRIVATE SM_WAVE_BUILD=1)
endfunction()
sm_add_sim_wave(stereo_sim_small_wave ${SM_SCENE_SMALL_DIR} ${SM_SMALL_PARAMS})
sm_add_sim_wave(stereo_sim_wave ${SM_SCENE_DIR} ${SM_PAPER_PARAMS})
if(NOT SM_WAVE_PAPER)
  set_target_properties(stereo_sim_wave stereo_sim_wave_lib PROPERTIES EXCLUDE_FROM_ALL ON)
endif()
