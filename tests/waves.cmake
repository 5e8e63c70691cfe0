if(NOT SM_WITH_TOP)
  return()
endif()
# Waves of one block (issue 22): stereo_sim --wave-scope / --wave-depth in the full-depth
# wave build, VCD and FST, the errors, and the GTKWave save files of waves/gtkw against
# dumps of their scopes (small configuration; the exact names at the paper configuration
# too when stereo_sim_wave is built, -DSM_WAVE_PAPER=ON).
add_executable(test_sim_waves ${CMAKE_SOURCE_DIR}/tests/test_sim_waves.cpp)
target_link_libraries(test_sim_waves PRIVATE Catch2::Catch2 fmt::fmt)
target_include_directories(test_sim_waves PRIVATE ${CMAKE_SOURCE_DIR}/tests/common ${CMAKE_SOURCE_DIR}/sim)
target_compile_options(test_sim_waves PRIVATE ${SM_WARNINGS})
target_compile_definitions(test_sim_waves PRIVATE SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_waves_tmp"
                                                  SM_GTKW_DIR="${CMAKE_SOURCE_DIR}/waves/gtkw"
                                                  SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>"
                                                  SM_STEREO_SIM_SMALL_WAVE="$<TARGET_FILE:stereo_sim_small_wave>")
add_dependencies(test_sim_waves stereo_sim_small stereo_sim_small_wave)
set(_sm_wave_timeout 600)
if(SM_WAVE_PAPER)
  target_compile_definitions(test_sim_waves PRIVATE SM_STEREO_SIM_WAVE="$<TARGET_FILE:stereo_sim_wave>")
  add_dependencies(test_sim_waves stereo_sim_wave)
  set(_sm_wave_timeout 1800)
endif()
add_test(NAME system_waves COMMAND test_sim_waves)
set_tests_properties(system_waves PROPERTIES LABELS "system" TIMEOUT ${_sm_wave_timeout})
