if(NOT SM_WITH_TOP)
  return()
endif()
# Waves of one block (issue 22): stereo_sim --wave-scope / --wave-depth in the full-depth
# wave build, VCD and FST, the errors, and the GTKWave save files of waves/gtkw against
# dumps of their scopes (small configuration; the exact names at the paper configuration
# too when stereo_sim_wave is built, -DSM_WAVE_PAPER=ON).
set(_sm_wave_timeout 600)
set(_sm_wave_defs)
set(_sm_wave_deps)
if(SM_WAVE_PAPER)
  set(_sm_wave_defs SM_STEREO_SIM_WAVE="$<TARGET_FILE:stereo_sim_wave>")
  set(_sm_wave_deps stereo_sim_wave)
  set(_sm_wave_timeout 1800)
endif()
sm_unit_test(test_sim_waves TEST system_waves LIBS fmt::fmt INCLUDES ${CMAKE_SOURCE_DIR}/tests/common ${CMAKE_SOURCE_DIR}/sim ${CMAKE_SOURCE_DIR}/model
             DEFINES SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_waves_tmp" SM_GTKW_DIR="${CMAKE_SOURCE_DIR}/waves/gtkw"
                     SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>"
                     SM_STEREO_SIM_SMALL_WAVE="$<TARGET_FILE:stereo_sim_small_wave>" ${_sm_wave_defs}
             DEPENDS stereo_sim_small stereo_sim_small_wave ${_sm_wave_deps} LABELS system TIMEOUT ${_sm_wave_timeout})
