# Pre-processing area: brightness + rectification block tests and model tests.
sm_rtl_test(NAME tb_brightness TOP sm_brightness
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_brightness.cpp)
sm_rtl_test(NAME tb_rectify_small TOP sm_rectify
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_rectify.cpp
            PARAMS MAX_WIDTH=64 MAX_HEIGHT=48 RECT_RADIUS=4)
sm_rtl_test(NAME tb_rectify_paper TOP sm_rectify
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_rectify.cpp
            PARAMS MAX_WIDTH=320 MAX_HEIGHT=240 RECT_RADIUS=15 LABELS "rtl;slow" TIMEOUT 300)

sm_unit_test(test_pre_model LIBS sm_model sm_toolio ${OpenCV_LIBS}
             INCLUDES ${OpenCV_INCLUDE_DIRS} ${CMAKE_CURRENT_LIST_DIR}/common
             DEFINES SM_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/pre_model_tmp")

# Calibration tool on a real chessboard set, only when its folder is given
# (-DSM_CHESSBOARD_DIR=../shared/datasets/chessboard): the default suite never depends on
# data outside the project. At alpha 0 the reference rig needs RECT_RADIUS 18.
set(SM_CHESSBOARD_DIR "" CACHE PATH "stereo chessboard images for the calibration tool tests")
if(SM_CHESSBOARD_DIR AND EXISTS "${SM_CHESSBOARD_DIR}/left01.jpg")
  set(_cal_out ${CMAKE_CURRENT_BINARY_DIR}/calib_test)
  file(MAKE_DIRECTORY ${_cal_out})
  add_test(NAME calibrate_chessboard
           COMMAND sm_calibrate ${SM_CHESSBOARD_DIR} --check-vdisp 0.5
                   -o ${_cal_out}/folder.json --yaml ${_cal_out}/folder.yaml)
  add_test(NAME calibrate_chessboard_list
           COMMAND sm_calibrate ${SM_CHESSBOARD_DIR}/stereo_calib.xml --rect-radius 20
                   --check-vdisp 0.5 -o ${_cal_out}/list.json --yaml ${_cal_out}/list.yaml)
  set_tests_properties(calibrate_chessboard calibrate_chessboard_list PROPERTIES LABELS unit)
  # alpha 0 needs a radius of 18 on this rig: the tool must refuse RECT_RADIUS 15
  add_test(NAME calibrate_radius_too_small
           COMMAND sm_calibrate ${SM_CHESSBOARD_DIR} --rect-radius 15
                   -o ${_cal_out}/small.json --yaml ${_cal_out}/small.yaml)
  set_tests_properties(calibrate_radius_too_small PROPERTIES LABELS robust PASS_REGULAR_EXPRESSION
                       "error: the rig needs RECT_RADIUS >= 18 but the IP is configured with 15")
endif()
add_test(NAME calibrate_bad_input COMMAND sm_calibrate /nonexistent/chessboard)
set_tests_properties(calibrate_bad_input PROPERTIES LABELS robust
                     PASS_REGULAR_EXPRESSION "/nonexistent/chessboard: no such file or folder")
add_test(NAME calibrate_bad_board COMMAND sm_calibrate ${CMAKE_CURRENT_LIST_DIR} --board 9by6)
set_tests_properties(calibrate_bad_board PROPERTIES LABELS robust
                     PASS_REGULAR_EXPRESSION "--board '9by6': expected")
