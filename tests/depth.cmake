# Metric depth, point clouds and pictures (issue 42) and the calibration tool's and file's
# bad inputs (issue 40): test_depth (tests/test_depth.cpp) registered three times by
# Catch2 tag -- test_depth (unit: library, calibration file, sm_calibrate's camera),
# system_depth_scene (system: stereo_model's depth of an sm_scene scene within 1 % of the
# truth), robust_depth_calib (robust: bad options, files and signals leave nothing) --
# and depth_cloud_plyfile (unit): the PLY read back by plyfile, the independent reader
# pinned in scripts/requirements.txt, from the project's .venv (SM_VENV, as pytools.cmake).
if(NOT (TARGET sm_toolio AND TARGET stereo_model AND TARGET sm_scene AND TARGET sm_calibrate AND TARGET sm_evaluate
        AND TARGET sm_ref_frames))
  return()
endif()
add_executable(test_depth ${CMAKE_CURRENT_LIST_DIR}/test_depth.cpp)
target_link_libraries(test_depth PRIVATE sm_toolio Catch2::Catch2 nlohmann_json::nlohmann_json)
target_include_directories(test_depth PRIVATE ${CMAKE_CURRENT_LIST_DIR}/common)
target_compile_options(test_depth PRIVATE ${SM_WARNINGS})
target_compile_definitions(test_depth PRIVATE SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/depth_tmp"
  SM_SCENE_EXE="$<TARGET_FILE:sm_scene>" SM_STEREO_MODEL_EXE="$<TARGET_FILE:stereo_model>"
  SM_CALIBRATE_EXE="$<TARGET_FILE:sm_calibrate>" SM_EVALUATE_EXE="$<TARGET_FILE:sm_evaluate>"
  SM_REF_FRAMES_EXE="$<TARGET_FILE:sm_ref_frames>")
add_dependencies(test_depth sm_scene stereo_model sm_calibrate sm_evaluate sm_ref_frames)
add_test(NAME test_depth COMMAND test_depth "~[system]~[robust]")
add_test(NAME system_depth_scene COMMAND test_depth "[system]")
add_test(NAME robust_depth_calib COMMAND test_depth "[robust]")
set_tests_properties(test_depth PROPERTIES LABELS "unit")
set_tests_properties(system_depth_scene PROPERTIES LABELS "system")
set_tests_properties(robust_depth_calib PROPERTIES LABELS "robust" TIMEOUT 300)
if(EXISTS ${SM_VENV}/bin/python)
  add_test(NAME depth_cloud_plyfile
           COMMAND ${SM_VENV}/bin/python ${CMAKE_CURRENT_LIST_DIR}/depth_cloud_check.py --scene-exe
                   $<TARGET_FILE:sm_scene> --model-exe $<TARGET_FILE:stereo_model>
                   --work ${CMAKE_CURRENT_BINARY_DIR}/depth_tmp/plyfile)
  set_tests_properties(depth_cloud_plyfile PROPERTIES LABELS "unit")
else()
  message(WARNING "${SM_VENV} not found: no depth_cloud_plyfile test (scripts/deps.sh makes it)")
endif()
