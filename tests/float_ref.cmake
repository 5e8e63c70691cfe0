# Floating-point reference (tools/float_ref, issue 21): known answer on a synthetic pair,
# bit-identical to the model with every simplification on (label unit; no ../shared).
if(TARGET sm_float_ref AND TARGET sm_toolio)
  sm_unit_test(test_float_ref LIBS sm_float_ref sm_toolio INCLUDES ${CMAKE_SOURCE_DIR}/tests/common DISCOVER)
endif()
