if(NOT SM_WITH_TOP)
  return()
endif()
# stereo_sim as a host drives the IP (issue 23): register files, a register schedule that
# changes every frame, the object list and status in the report, bad register files;
# and stereo_sim's standard outputs (lossless disparity, resized ground truth, ranges).
# Small configuration: each run takes well under a second.
sm_unit_test(test_sim_host TEST system_sim_host LIBS sm_toolio nlohmann_json::nlohmann_json ${OpenCV_LIBS}
             INCLUDES ${CMAKE_SOURCE_DIR}/tests/common
             DEFINES SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_host_tmp"
                     SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>"
             DEPENDS stereo_sim_small LABELS system TIMEOUT 600)
