# sm_toolio: helpers shared by every tool (image I/O with one-line errors, all-or-nothing
# output sets, colour maps, dataset reader, bad-1.0 metric, synthetic scene generator).
# Included by tools/calib.cmake, tools/scene.cmake and tools/model_tools.cmake, whichever
# comes first.
include_guard(GLOBAL)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)
add_library(sm_toolio STATIC ${CMAKE_CURRENT_LIST_DIR}/sm_io.cpp ${CMAKE_CURRENT_LIST_DIR}/sm_outputs.cpp
                             ${CMAKE_CURRENT_LIST_DIR}/sm_scenegen.cpp ${CMAKE_CURRENT_LIST_DIR}/sm_regs_json.cpp)
target_include_directories(sm_toolio PUBLIC ${CMAKE_CURRENT_LIST_DIR}/.. ${OpenCV_INCLUDE_DIRS})
# the register file parser (sm_regs_json) takes its names and ranges from the generated map
target_include_directories(sm_toolio PRIVATE ${SM_GEN_DIR})
add_dependencies(sm_toolio sm_regmap_gen_files)
target_link_libraries(sm_toolio PUBLIC sm_model opencv_core opencv_imgproc opencv_imgcodecs
                                       fmt::fmt nlohmann_json::nlohmann_json)
target_compile_options(sm_toolio PRIVATE ${SM_WARNINGS})
