# WTA record of the output stage (docs/algorithm.md section 9.0): block tests of sm_wta
# against the model's wta_row / wta_band (tests/tb_wta.cpp).

# Small point, one beat per clock (LATENCY 4), odd width; full ce rate.
sm_rtl_test(NAME tb_wta TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=16 CW=4 PU=16 ARGS --width 37 --rows 9 --frames 3)
sm_rtl_test(NAME tb_wta_noidle RUN tb_wta ARGS --width 23 --rows 7 --frames 2 --seed 5 --idle 0)
# Folded: F = 2, 4, 8 (ring of 3, 2, 1 slots), random ce gaps and none.
sm_rtl_test(NAME tb_wta_pu8 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=16 CW=4 PU=8 ARGS --width 37 --rows 8 --frames 3 --seed 2)
sm_rtl_test(NAME tb_wta_pu8_noidle RUN tb_wta_pu8 ARGS --width 29 --rows 6 --frames 2 --seed 9 --idle 0)
sm_rtl_test(NAME tb_wta_pu4 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=16 CW=4 PU=4 ARGS --width 41 --rows 8 --frames 3 --seed 3)
sm_rtl_test(NAME tb_wta_pu4_noidle RUN tb_wta_pu4 ARGS --width 23 --rows 6 --frames 2 --seed 10 --idle 0)
sm_rtl_test(NAME tb_wta_pu2 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=16 CW=4 PU=2 ARGS --width 37 --rows 8 --frames 3 --seed 4 --idle 50)
# Neither DISP nor PU a power of two: DISP 10 (odd node counts pass through) at PU 10
# and F 5; DISP 12 at PU 6 (F 2, ring of 3).
sm_rtl_test(NAME tb_wta_odd TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=10 CW=3 PU=10 ARGS --width 23 --rows 9 --frames 3 --seed 6)
sm_rtl_test(NAME tb_wta_odd_pu2 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=10 CW=3 PU=2 ARGS --width 23 --rows 8 --frames 3 --seed 7)
sm_rtl_test(NAME tb_wta_pu6 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=12 CW=3 PU=6 ARGS --width 31 --rows 8 --frames 3 --seed 8)
sm_rtl_test(NAME tb_wta_pu6_noidle RUN tb_wta_pu6 ARGS --width 19 --rows 6 --frames 2 --seed 12 --idle 0)
# The fewest levels (DISP 4, CW 2): c2 has one or two levels to choose from; folded to
# PU 2 (F 2).
sm_rtl_test(NAME tb_wta_d4 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=4 CW=2 PU=4 ARGS --width 17 --rows 6 --frames 3 --seed 15)
sm_rtl_test(NAME tb_wta_d4_pu2 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=4 CW=2 PU=2 ARGS --width 17 --rows 6 --frames 3 --seed 16)
# Paper (DISP 128, CW 6 = CENSUS 15 >> 2, PU 128: LATENCY 7) and zynq/vga (PU 16, 8).
sm_rtl_test(NAME tb_wta_paper TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=128 CW=6 PU=128 ARGS --width 320 --rows 6 --frames 3 --seed 11
            LABELS "rtl;slow")
sm_rtl_test(NAME tb_wta_zynq16 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=128 CW=6 PU=16 ARGS --width 320 --rows 4 --frames 3 --seed 13
            LABELS "rtl;slow")
sm_rtl_test(NAME tb_wta_zynq8 TOP sm_wta SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_wta.cpp
            PARAMS DISP=128 CW=6 PU=8 ARGS --width 251 --rows 4 --frames 3 --seed 14
            LABELS "rtl;slow")
