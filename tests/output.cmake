# Output stage (docs/algorithm.md section 9: sub-pixel, validity, confidence): model tests.
sm_unit_test(test_output_model LIBS sm_toolio INCLUDES ${CMAKE_SOURCE_DIR}/tests/common DISCOVER)
