# Calibration tool: chessboard stereo calibration -> rectifier grid registers (JSON).
add_executable(sm_calibrate ${CMAKE_CURRENT_LIST_DIR}/sm_calibrate.cpp)
target_link_libraries(sm_calibrate PRIVATE sm_model sm_toolio ${OpenCV_LIBS} CLI11::CLI11 fmt::fmt)
target_include_directories(sm_calibrate PRIVATE ${OpenCV_INCLUDE_DIRS})
target_compile_options(sm_calibrate PRIVATE ${SM_WARNINGS})
