# Yosys synthesis flow (docs/synthesis.md): sm_synth_report (stat / netlist -> report
# JSON) and the custom targets that regenerate build/synth/<top>_<config>.json, which
# stereo_sim reads for its report. Nothing here is built by default: synthesis takes
# minutes (small configuration) to hours (paper configuration).
add_executable(sm_synth_report ${CMAKE_CURRENT_SOURCE_DIR}/sm_synth_report.cpp
                               ${CMAKE_CURRENT_SOURCE_DIR}/sm_pnr_report.cpp)
target_link_libraries(sm_synth_report PRIVATE fmt::fmt CLI11::CLI11
                                              nlohmann_json::nlohmann_json)
target_compile_options(sm_synth_report PRIVATE ${SM_WARNINGS})
# toolio/sm_cli.hpp (and sm_json_file.hpp): header-only, no link to sm_toolio
target_include_directories(sm_synth_report PRIVATE ${CMAKE_SOURCE_DIR})

set(SM_SYNTH_DRIVER ${CMAKE_CURRENT_SOURCE_DIR}/synth/sm_synth.sh)
set(SM_SYNTH_DIR ${CMAKE_BINARY_DIR}/synth)
# The configurations of the top-level CMakeLists.txt.
set(SM_SYNTH_SMALL_PARAMS ${SM_SMALL_PARAMS})
set(SM_SYNTH_PAPER_PARAMS ${SM_PAPER_PARAMS})
set(SM_SYNTH_ZYNQ_PARAMS ${SM_ZYNQ_PARAMS})
set(SM_SYNTH_TIMEOUT 14400 CACHE STRING "time limit (s) of one Yosys run of the synth targets")
option(SM_SYNTH_PAPER_BLOCKS
       "the whole-core targets map each block of sm_top in its own Yosys run and sum them" ON)
option(SM_SYNTH_ON_BUILD "regenerate the small-configuration synthesis report on every build"
       OFF)

# sm_synth_command(<out var> TOP <module> CONFIG <name> FAMILY <family> PARAMS ... [BLOCKS])
function(sm_synth_command var)
  cmake_parse_arguments(S "BLOCKS" "TOP;CONFIG;FAMILY" "PARAMS" ${ARGN})
  set(cmd ${SM_SYNTH_DRIVER} -t ${S_TOP} -c ${S_CONFIG} -f ${S_FAMILY} -o ${SM_SYNTH_DIR}
      -x $<TARGET_FILE:sm_synth_report> -L ${SM_GEN_DIR} -T ${SM_SYNTH_TIMEOUT})
  foreach(p ${S_PARAMS})
    list(APPEND cmd -p ${p})
  endforeach()
  if(S_BLOCKS)
    list(APPEND cmd -B)
  endif()
  set(${var} ${cmd} PARENT_SCOPE)
endfunction()

# Whole IP, the configurations of stereo_sim_small / stereo_sim. The harness reads
# sm_top_<sim target>.json; the other family gets a _<family> suffix.
# Blocks mode elaborates every block on its own, so a block's figures move only with its
# own RTL (docs/synthesis.md, "Flow").
set(blocks)
if(SM_SYNTH_PAPER_BLOCKS)
  set(blocks BLOCKS)
endif()
sm_synth_command(c_small_xc7 TOP sm_top CONFIG stereo_sim_small FAMILY xc7
                 PARAMS ${SM_SYNTH_SMALL_PARAMS} ${blocks})
sm_synth_command(c_small_xc5v TOP sm_top CONFIG stereo_sim_small_xc5v FAMILY xc5v
                 PARAMS ${SM_SYNTH_SMALL_PARAMS} ${blocks})
sm_synth_command(c_paper_xc5v TOP sm_top CONFIG stereo_sim FAMILY xc5v
                 PARAMS ${SM_SYNTH_PAPER_PARAMS} ${blocks})
sm_synth_command(c_paper_xc7 TOP sm_top CONFIG stereo_sim_xc7 FAMILY xc7
                 PARAMS ${SM_SYNTH_PAPER_PARAMS} ${blocks})
# the Zynq-7000's family (xc7z020 budget: docs/synthesis.md)
sm_synth_command(c_zynq_xc7 TOP sm_top CONFIG stereo_sim_zynq FAMILY xc7
                 PARAMS ${SM_SYNTH_ZYNQ_PARAMS} ${blocks})
sm_synth_command(c_vga_xc7 TOP sm_top CONFIG stereo_sim_vga FAMILY xc7 PARAMS ${SM_VGA_PARAMS} ${blocks})
set(all)
if(SM_SYNTH_ON_BUILD)
  set(all ALL)
endif()
add_custom_target(synth_small ${all}
  COMMAND ${c_small_xc7}
  COMMAND ${c_small_xc5v}
  DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys: sm_top at the small configuration (xc7, xc5v)")
add_custom_target(synth_paper
  COMMAND ${c_paper_xc5v}
  DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys: sm_top at the paper configuration (xc5v; hours on 2 cores)")
add_custom_target(synth_paper_xc7
  COMMAND ${c_paper_xc7}
  DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys: sm_top at the paper configuration (xc7)")

add_custom_target(synth_zynq
  COMMAND ${c_zynq_xc7}
  DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys: sm_top at the zynq configuration (xc7, PU ${SM_ZYNQ_PU})")

add_custom_target(synth_vga
  COMMAND ${c_vga_xc7}
  DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys: sm_top at the vga configuration (640x480, xc7, PU ${SM_ZYNQ_PU})")

# Place and route on a Lattice ECP5 (LFE5U-85F, speed grade 6; SM_NEXTPNR_ECP5):
# the achieved clock, not only the LUT levels. The small configurations fit the part whole;
# zynq does not (133,415 LUT4s in the committed report against 83,640), so its blocks are
# placed one by one.
set(c_pnr ${SM_SYNTH_DRIVER} -t sm_top -f ecp5 -N ${SM_NEXTPNR_ECP5} -o ${SM_SYNTH_DIR}
    -x $<TARGET_FILE:sm_synth_report> -L ${SM_GEN_DIR} -T ${SM_SYNTH_TIMEOUT})
set(c_pnr_small ${c_pnr} -c stereo_sim_small_ecp5)
foreach(p ${SM_SYNTH_SMALL_PARAMS})
  list(APPEND c_pnr_small -p ${p})
endforeach()
set(c_pnr_small_fold ${c_pnr} -c stereo_sim_small_fold_ecp5)
foreach(p ${SM_SMALL_FOLD_PARAMS})
  list(APPEND c_pnr_small_fold -p ${p})
endforeach()
set(c_pnr_zynq ${c_pnr} -c stereo_sim_zynq_ecp5 -B)
foreach(p ${SM_SYNTH_ZYNQ_PARAMS})
  list(APPEND c_pnr_zynq -p ${p})
endforeach()
add_custom_target(pnr_small COMMAND ${c_pnr_small} DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys + nextpnr-ecp5: sm_top at the small configuration (~12 min)")
add_custom_target(pnr_small_fold COMMAND ${c_pnr_small_fold} DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys + nextpnr-ecp5: sm_top at the small configuration folded (PU 4)")
add_custom_target(pnr_zynq COMMAND ${c_pnr_zynq} DEPENDS sm_synth_report USES_TERMINAL
  COMMENT "Yosys + nextpnr-ecp5: the blocks of sm_top at the zynq configuration, one by one")

# sm_axil_regs includes the generated register map.
foreach(t synth_small synth_paper synth_paper_xc7 synth_zynq synth_vga pnr_small pnr_small_fold pnr_zynq)
  add_dependencies(${t} sm_regmap_gen_files)
endforeach()

# Every block on its own: synth_blocks_small / synth_blocks_paper (xc5v) write
# build/synth/<block>_small.json / <block>_paper.json. One Yosys at a time.
file(GLOB SM_SYNTH_RTL CONFIGURE_DEPENDS ${SM_RTL_DIR}/sm_*.v)
set(c_bs)
set(c_bp)
foreach(f ${SM_SYNTH_RTL})
  get_filename_component(m ${f} NAME_WE)
  sm_synth_command(c TOP ${m} CONFIG small FAMILY xc7 PARAMS ${SM_SYNTH_SMALL_PARAMS})
  list(APPEND c_bs COMMAND ${c})
  sm_synth_command(c TOP ${m} CONFIG paper FAMILY xc5v PARAMS ${SM_SYNTH_PAPER_PARAMS})
  list(APPEND c_bp COMMAND ${c})
endforeach()
add_custom_target(synth_blocks_small ${c_bs} DEPENDS sm_synth_report USES_TERMINAL
                  COMMENT "Yosys: every block at the small configuration (xc7)")
add_custom_target(synth_blocks_paper ${c_bp} DEPENDS sm_synth_report USES_TERMINAL
                  COMMENT "Yosys: every block at the paper configuration (xc5v)")
add_dependencies(synth_blocks_small sm_regmap_gen_files)
add_dependencies(synth_blocks_paper sm_regmap_gen_files)
