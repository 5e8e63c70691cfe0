# Right-view WTA (docs/algorithm.md section 9.0, field lr): block tests of sm_right_wta
# against the model's right_wta, line by line. The block needs no minimum width: widths
# below DISP - 1 (the pixel leaving is then rows back), width 1 and full width; no idle
# cycles (--idle 0) and long gaps (--idle 60).
sm_rtl_test(NAME tb_right_wta TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=16 ARGS --width 37 --rows 9 --frames 3)
sm_rtl_test(NAME tb_right_wta_w64 RUN tb_right_wta ARGS --width 64 --rows 6 --frames 2 --seed 7 --idle 0)
sm_rtl_test(NAME tb_right_wta_w15 RUN tb_right_wta ARGS --width 15 --rows 7 --frames 3 --seed 3)
sm_rtl_test(NAME tb_right_wta_w5 RUN tb_right_wta ARGS --width 5 --rows 9 --frames 4 --seed 5 --idle 60)
sm_rtl_test(NAME tb_right_wta_w1 RUN tb_right_wta ARGS --width 1 --rows 11 --frames 5 --seed 2)

# Folded (PU < DISP, F = DISP/PU clocks per beat, ce at most every F clocks, input held
# between ces): DISP 16 at PU 8, 4, 2 (F 2, 4, 8); F not a power of two (DISP 10, PU 2:
# F 5) and PU not a power of two (DISP 12, PU 6).
sm_rtl_test(NAME tb_right_wta_pu8 TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=8 ARGS --width 37 --rows 9 --frames 3)
sm_rtl_test(NAME tb_right_wta_pu8_w3 RUN tb_right_wta_pu8 ARGS --width 3 --rows 8 --frames 3 --seed 4 --idle 60)
sm_rtl_test(NAME tb_right_wta_pu4 TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=4 ARGS --width 41 --rows 8 --frames 3 --seed 2)
sm_rtl_test(NAME tb_right_wta_pu4_w7 RUN tb_right_wta_pu4 ARGS --width 7 --rows 8 --frames 3 --seed 8 --idle 0)
sm_rtl_test(NAME tb_right_wta_pu2 TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=2 ARGS --width 37 --rows 8 --frames 3 --seed 9)
sm_rtl_test(NAME tb_right_wta_pu2_w1 RUN tb_right_wta_pu2 ARGS --width 1 --rows 9 --frames 4 --seed 13 --idle 0)
sm_rtl_test(NAME tb_right_wta_odd TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=50 DISP=10 CW=3 PU=10 ARGS --width 23 --rows 8 --frames 3)
sm_rtl_test(NAME tb_right_wta_odd_w7 RUN tb_right_wta_odd ARGS --width 7 --rows 8 --frames 3 --seed 6)
sm_rtl_test(NAME tb_right_wta_odd_pu2 TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=50 DISP=10 CW=3 PU=2 ARGS --width 23 --rows 8 --frames 3 --seed 6)
sm_rtl_test(NAME tb_right_wta_odd_pu2_w9 RUN tb_right_wta_odd_pu2 ARGS --width 9 --rows 8 --frames 3 --seed 10)
sm_rtl_test(NAME tb_right_wta_pu6 TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=50 DISP=12 CW=3 PU=6 ARGS --width 31 --rows 8 --frames 3 --seed 8)
sm_rtl_test(NAME tb_right_wta_pu6_w11 RUN tb_right_wta_pu6 ARGS --width 11 --rows 8 --frames 3 --seed 12 --idle 60)

# Paper (PU 128) and zynq (PU 8) points: full width, and the core's minimum width at
# DISP 128 (67, sm_dp's DISP/2 + 3, below DISP - 1).
sm_rtl_test(NAME tb_right_wta_paper TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CW=6 PU=128 ARGS --width 320 --rows 6 --frames 3
            LABELS "rtl;slow")
sm_rtl_test(NAME tb_right_wta_paper_w67 RUN tb_right_wta_paper
            ARGS --width 67 --rows 8 --frames 3 --seed 4 LABELS "rtl;slow")
sm_rtl_test(NAME tb_right_wta_zynq8 TOP sm_right_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_right_wta.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CW=6 PU=8 ARGS --width 320 --rows 5 --frames 3 --seed 12
            LABELS "rtl;slow")
sm_rtl_test(NAME tb_right_wta_zynq8_w67 RUN tb_right_wta_zynq8
            ARGS --width 67 --rows 6 --frames 3 --seed 5 LABELS "rtl;slow")
sm_rtl_test(NAME tb_right_wta_paper_w9 RUN tb_right_wta_paper
            ARGS --width 9 --rows 7 --frames 3 --seed 6 --idle 60 LABELS "rtl;slow")
