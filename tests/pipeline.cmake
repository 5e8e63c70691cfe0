# The whole model pipeline (run_pipeline): thread counts and the stage functions agree.
sm_unit_test(test_pipeline_model LIBS sm_model DISCOVER)
