if(NOT SM_WITH_TOP)
  return()
endif()
# stereo_sim's metric depth, point cloud, pictures, wave time stamps, progress, default
# scene and register ranges in --help (issue 42), on the small configuration.
sm_unit_test(test_sim_depth TEST system_sim_depth LIBS sm_toolio nlohmann_json::nlohmann_json ${OpenCV_LIBS}
             INCLUDES ${CMAKE_SOURCE_DIR}/tests/common
             DEFINES SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/sim_depth_tmp"
                     SM_STEREO_SIM_SMALL="$<TARGET_FILE:stereo_sim_small>" SM_SCENE_SMALL_DIR="${SM_SCENE_SMALL_DIR}"
             DEPENDS stereo_sim_small LABELS system TIMEOUT 600)
