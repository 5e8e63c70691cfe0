if(NOT SM_WITH_TOP)
  return()
endif()
# stereo_sim as a host drives the IP (issue 23): register files, a register schedule that
# changes every frame, the object list and status in the report, bad register files;
# and stereo_sim's standard outputs (lossless disparity, resized ground truth, ranges).
# Small configuration: each run takes well under a second.
add_executable(test_sim_host ${CMAKE_SOURCE_DIR}/tests/test_sim_host.cpp)
target_link_libraries(test_sim_host PRIVATE sm_toolio Catch2::Catch2 nlohmann_json::nlohmann_json ${OpenCV_LIBS})
target_include_directories(test_sim_host PRIVATE ${CMAKE_SOURCE_DIR}/tests/common)
target_compile_options(test_sim_host PRIVATE ${SM_WARNINGS})
target_compile_definitions(test_sim_host PRIVATE SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_host_tmp"
                                                 SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>")
add_dependencies(test_sim_host stereo_sim_small)
add_test(NAME system_sim_host COMMAND test_sim_host)
set_tests_properties(system_sim_host PROPERTIES LABELS "system" TIMEOUT 600)
