# Floating-point reference of the pipeline (issue 21; docs/evaluation.md, "What each
# fixed-point simplification costs"): library sm_float_ref (tools/float_ref/, used by the
# tool and its unit test) and the tool sm_float_ref. Not part of the IP or the model.
add_library(sm_float_ref STATIC ${CMAKE_CURRENT_LIST_DIR}/float_ref/float_ref.cpp)
target_include_directories(sm_float_ref PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(sm_float_ref PUBLIC sm_model fmt::fmt)
target_compile_options(sm_float_ref PRIVATE ${SM_WARNINGS})

add_executable(sm_float_ref_tool ${CMAKE_CURRENT_LIST_DIR}/sm_float_ref.cpp)
set_target_properties(sm_float_ref_tool PROPERTIES OUTPUT_NAME sm_float_ref)
target_link_libraries(sm_float_ref_tool PRIVATE sm_float_ref sm_toolio CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(sm_float_ref_tool PRIVATE ${SM_WARNINGS})
