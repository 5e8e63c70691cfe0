# Floating-point reference (tools/float_ref, issue 21): known answer on a synthetic pair,
# bit-identical to the model with every simplification on (label unit; no ../shared).
if(TARGET sm_float_ref AND TARGET sm_toolio)
  add_executable(test_float_ref ${CMAKE_CURRENT_LIST_DIR}/test_float_ref.cpp)
  target_link_libraries(test_float_ref PRIVATE sm_float_ref sm_toolio Catch2::Catch2)
  target_compile_options(test_float_ref PRIVATE ${SM_WARNINGS})
  catch_discover_tests(test_float_ref PROPERTIES LABELS unit)
endif()
