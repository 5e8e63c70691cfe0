# Tests of the tools around the model (label unit): scene generator, shared helpers and
# the command-line tools (bad inputs, outputs). They do not use ../shared.
if(TARGET sm_toolio AND TARGET stereo_model AND TARGET sm_evaluate AND TARGET sm_calibrate)
  set(SM_TOOLS_TEST_TMP ${CMAKE_CURRENT_BINARY_DIR}/tools_tmp)
  foreach(t test_scene test_tools_io test_tools_cli)
    add_executable(${t} ${CMAKE_CURRENT_LIST_DIR}/${t}.cpp)
    target_link_libraries(${t} PRIVATE sm_toolio Catch2::Catch2 nlohmann_json::nlohmann_json)
    target_include_directories(${t} PRIVATE ${CMAKE_CURRENT_LIST_DIR}/common)
    target_compile_options(${t} PRIVATE ${SM_WARNINGS})
    target_compile_definitions(${t} PRIVATE SM_TEST_TMP="${SM_TOOLS_TEST_TMP}/${t}"
      SM_SCENE_EXE="$<TARGET_FILE:sm_scene>" SM_STEREO_MODEL_EXE="$<TARGET_FILE:stereo_model>"
      SM_EVALUATE_EXE="$<TARGET_FILE:sm_evaluate>" SM_CALIBRATE_EXE="$<TARGET_FILE:sm_calibrate>")
    add_test(NAME ${t} COMMAND ${t})
    set_tests_properties(${t} PROPERTIES LABELS "unit")
  endforeach()
  # The CLI tests run the tools themselves.
  add_dependencies(test_tools_cli sm_scene stereo_model sm_evaluate sm_calibrate)
  add_dependencies(test_scene sm_scene)
endif()

# Bad inputs to the tools, one test case per class (label robust, docs/robustness.md
# "Tools"): exit code, the one error line naming the file or option, no output left.
if(TARGET sm_toolio AND TARGET stereo_model AND TARGET sm_evaluate AND TARGET sm_synth_report AND TARGET sm_coverage
   AND TARGET sm_output_study)
  add_executable(test_tools_robust ${CMAKE_CURRENT_LIST_DIR}/test_tools_robust.cpp)
  target_link_libraries(test_tools_robust PRIVATE sm_toolio Catch2::Catch2 nlohmann_json::nlohmann_json)
  target_include_directories(test_tools_robust PRIVATE ${CMAKE_CURRENT_LIST_DIR}/common)
  target_compile_options(test_tools_robust PRIVATE ${SM_WARNINGS})
  target_compile_definitions(
    test_tools_robust PRIVATE SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tools_tmp/test_tools_robust"
    SM_SCENE_EXE="$<TARGET_FILE:sm_scene>" SM_STEREO_MODEL_EXE="$<TARGET_FILE:stereo_model>"
    SM_EVALUATE_EXE="$<TARGET_FILE:sm_evaluate>" SM_SYNTH_REPORT_EXE="$<TARGET_FILE:sm_synth_report>"
    SM_COVERAGE_EXE="$<TARGET_FILE:sm_coverage>" SM_REGMAP_GEN_EXE="$<TARGET_FILE:sm_regmap_gen>"
    SM_OUTPUT_STUDY_EXE="$<TARGET_FILE:sm_output_study>" SM_SCALE_DATASET_EXE="$<TARGET_FILE:bench_scale_dataset>")
  add_test(NAME test_tools_robust COMMAND test_tools_robust)
  set_tests_properties(test_tools_robust PROPERTIES LABELS "robust")
  add_dependencies(test_tools_robust sm_scene stereo_model sm_evaluate sm_synth_report sm_coverage sm_regmap_gen
                   sm_output_study bench_scale_dataset)  # bench/ is added after tests/: no TARGET check
endif()
