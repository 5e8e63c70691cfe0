# The whole model pipeline (run_pipeline): thread counts and the stage functions agree.
sm_unit_test(test_pipeline_model LIBS sm_model DISCOVER)
add_test(NAME test_pipeline_model_no_avx512 COMMAND test_pipeline_model)
set_tests_properties(test_pipeline_model_no_avx512 PROPERTIES LABELS unit ENVIRONMENT SM_NO_AVX512=1)
