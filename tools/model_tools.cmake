# Tools around the reference model: stereo_model (one pair -> disparity PNGs) and
# sm_evaluate (bad-1.0 / run time against OpenCV matchers, docs/evaluation.md).
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs calib3d stereo)

add_executable(stereo_model ${CMAKE_CURRENT_LIST_DIR}/stereo_model.cpp)
target_link_libraries(stereo_model PRIVATE sm_toolio CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(stereo_model PRIVATE ${SM_WARNINGS})

add_executable(sm_evaluate ${CMAKE_CURRENT_LIST_DIR}/sm_evaluate.cpp)
target_link_libraries(sm_evaluate PRIVATE sm_toolio CLI11::CLI11 nlohmann_json::nlohmann_json
                                          opencv_calib3d opencv_stereo)
target_compile_options(sm_evaluate PRIVATE ${SM_WARNINGS})
