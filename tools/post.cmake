# Post-processing filter study (docs/algorithm.md section 7).
add_executable(sm_filter_study ${CMAKE_CURRENT_LIST_DIR}/sm_filter_study.cpp)
target_link_libraries(sm_filter_study PRIVATE sm_toolio CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(sm_filter_study PRIVATE ${SM_WARNINGS})

# Output-stage study: sub-pixel estimators, validity rules, confidence (docs/evaluation.md).
# The bound study trains OpenCV's random forest (opencv_ml, part of Debian's libopencv-dev).
find_package(OpenCV REQUIRED COMPONENTS ml)
add_library(sm_output_bound STATIC ${CMAKE_CURRENT_LIST_DIR}/sm_output_bound.cpp)
target_include_directories(sm_output_bound PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(sm_output_bound PUBLIC sm_toolio opencv_ml)
target_compile_options(sm_output_bound PRIVATE ${SM_WARNINGS})
# The speckle check of a disparity map, ideal and in the IP's form (model/speckle.hpp)
# (sm_output_study --study speckle).
add_library(sm_speckle STATIC ${CMAKE_CURRENT_LIST_DIR}/sm_speckle.cpp ${CMAKE_CURRENT_LIST_DIR}/sm_speckle_table.cpp)
target_include_directories(sm_speckle PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(sm_speckle PUBLIC opencv_core sm_model)
target_compile_options(sm_speckle PRIVATE ${SM_WARNINGS})
# The trellis's min-marginals (sm_output_study --study dp-margin).
add_library(sm_dp_margin STATIC ${CMAKE_CURRENT_LIST_DIR}/sm_dp_margin.cpp)
target_include_directories(sm_dp_margin PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_compile_options(sm_dp_margin PRIVATE ${SM_WARNINGS})
# Wider window supports as a confidence cue (sm_output_study --study window-conf).
add_library(sm_window_support STATIC ${CMAKE_CURRENT_LIST_DIR}/sm_window_support.cpp)
target_include_directories(sm_window_support PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(sm_window_support PUBLIC sm_model)
target_compile_options(sm_window_support PRIVATE ${SM_WARNINGS})
add_executable(sm_output_study ${CMAKE_CURRENT_LIST_DIR}/sm_output_study.cpp)
target_link_libraries(sm_output_study PRIVATE sm_output_bound sm_speckle sm_dp_margin sm_window_support CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(sm_output_study PRIVATE ${SM_WARNINGS})
