if(NOT SM_WITH_TOP)
  return()
endif()
# stereo_sim on bad input (issue 40): one ctest per class of bad input, each a [tag] of
# test_sim_robust, asserting the exit code, the one-line message and that nothing was
# written (docs/robustness.md "Tools"). Small configurations: each run is well under a
# second, except the Ctrl-C case, which waits for a wave dump to start.
add_executable(test_sim_robust ${CMAKE_SOURCE_DIR}/tests/test_sim_robust.cpp)
target_link_libraries(test_sim_robust PRIVATE sm_model sm_toolio nlohmann_json::nlohmann_json ${OpenCV_LIBS}
                                              Catch2::Catch2)
target_include_directories(test_sim_robust PRIVATE ${CMAKE_SOURCE_DIR}/tests/common ${CMAKE_SOURCE_DIR}/model)
target_compile_options(test_sim_robust PRIVATE ${SM_WARNINGS})
target_compile_definitions(test_sim_robust PRIVATE SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_robust_tmp"
                                                   SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>"
                                                   SM_STEREO_SIM_SMALL_FOLD="$<TARGET_FILE:stereo_sim_small_fold>")
add_dependencies(test_sim_robust stereo_sim_small stereo_sim_small_fold)
foreach(class synth_json disp_file wave_path name_clash exclusive numbers scene input_files calib video resized_note
              frame_period budget sigint merge)
  # each class in its own temporary folder, so that the tests can run in parallel
  add_test(NAME robust_sim_${class} COMMAND test_sim_robust "[${class}]")
  set_tests_properties(robust_sim_${class} PROPERTIES LABELS "robust" TIMEOUT 300 ENVIRONMENT
                                                                                  "SM_ROBUST_CLASS=${class}")
endforeach()
