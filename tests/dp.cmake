# Trellis DP (docs/algorithm.md section 6): model unit tests and block tests of sm_dp.
sm_unit_test(test_dp_model LIBS sm_model DISCOVER)

# Small point (CW = 4 is CENSUS 7 >> COST_SHIFT 2): odd width and full width.
sm_rtl_test(NAME tb_dp TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=16 ARGS --width 37 --rows 9 --frames 3)
sm_rtl_test(NAME tb_dp_w64 RUN tb_dp ARGS --width 64 --rows 7 --frames 2 --seed 7)
# Minimum active width S + P + 1 = 11.
sm_rtl_test(NAME tb_dp_wmin RUN tb_dp ARGS --width 11 --rows 6 --frames 2 --seed 3)
# Neither MAX_WIDTH nor DISP a power of two (CW = 3 is CENSUS 5 >> 2).
sm_rtl_test(NAME tb_dp_odd TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=50 DISP=10 CW=3 ARGS --width 23 --rows 8 --frames 3)
# Every skew of 2 beats or more in a LUT-RAM ring (sm_dp RING_MIN = 2; by default
# only the paper configuration's long skews are rings): ring depths 2, 4 and 8, below
# the pointer width's 8 and equal to the skew (2, 4) or deeper (3, 5).
sm_rtl_test(NAME tb_dp_ring TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=50 DISP=10 CW=3 RING_MIN=2 ARGS --width 29 --rows 8 --frames 3)
sm_rtl_test(NAME tb_dp_ring16 RUN tb_dp_ring ARGS --width 50 --rows 5 --frames 2 --seed 11)
# Paper configuration.
sm_rtl_test(NAME tb_dp_paper TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CW=6 ARGS --width 320 --rows 8 --frames 3
            LABELS "rtl;slow")
sm_rtl_test(NAME tb_dp_paper_wmin RUN tb_dp_paper
            ARGS --width 67 --rows 6 --frames 3 --seed 4 LABELS "rtl;slow")

# Folded (PU < DISP, F = DISP/PU clocks per beat, ce at most every F clocks, input held
# between ces): DISP 16 at PU 8, 4, 2 (F 2, 4, 8), odd and minimum widths, random ce
# gaps; F not a power of two (DISP 10, PU 2: F 5) and PU not a power of two (DISP 12,
# PU 6); the zynq point (DISP 128, CW 6 = CENSUS 15, PU 16 and 8).
sm_rtl_test(NAME tb_dp_pu8 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=8 ARGS --width 37 --rows 9 --frames 3)
sm_rtl_test(NAME tb_dp_pu8_w64 RUN tb_dp_pu8 ARGS --width 64 --rows 6 --frames 3 --seed 5 --idle 60)
sm_rtl_test(NAME tb_dp_pu4 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=4 ARGS --width 41 --rows 8 --frames 3 --seed 2)
sm_rtl_test(NAME tb_dp_pu2 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 PU=2 ARGS --width 37 --rows 8 --frames 3 --seed 9)
sm_rtl_test(NAME tb_dp_pu2_wmin RUN tb_dp_pu2 ARGS --width 11 --rows 6 --frames 3 --seed 13 --idle 0)
sm_rtl_test(NAME tb_dp_odd_pu2 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=50 DISP=10 CW=3 PU=2 ARGS --width 23 --rows 8 --frames 3 --seed 6)
sm_rtl_test(NAME tb_dp_pu6 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=50 DISP=12 CW=3 PU=6 ARGS --width 31 --rows 8 --frames 3 --seed 8)
# F = 3 (DISP 12, PU 4): the least F at which the skew rings are written a clock late,
# one clock ahead of the word's first read when the lines are full width and the ce gaps
# exactly F clocks (--idle 0: a ring written two clocks late fails there); and at an odd
# width with random gaps. F = 4 at full width with gaps of exactly F clocks.
sm_rtl_test(NAME tb_dp_f3 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=50 DISP=12 CW=3 PU=4 ARGS --width 50 --rows 6 --frames 3 --seed 14 --idle 0)
sm_rtl_test(NAME tb_dp_f3_idle RUN tb_dp_f3 ARGS --width 29 --rows 8 --frames 3 --seed 10)
sm_rtl_test(NAME tb_dp_pu4_full RUN tb_dp_pu4 ARGS --width 64 --rows 6 --frames 3 --seed 15 --idle 0)
sm_rtl_test(NAME tb_dp_zynq16 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CW=6 PU=16 ARGS --width 320 --rows 5 --frames 3
            LABELS "rtl;slow")
sm_rtl_test(NAME tb_dp_zynq16_wmin RUN tb_dp_zynq16
            ARGS --width 67 --rows 6 --frames 3 --seed 4 LABELS "rtl;slow")
sm_rtl_test(NAME tb_dp_zynq8 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CW=6 PU=8 ARGS --width 251 --rows 4 --frames 3 --seed 12
            LABELS "rtl;slow")

# Edge flags of the DP's occlusion penalty (sm_edge_flag) against the model's
# edge_penalties, delayed by the aggregation's R rows and R + 6 beats: SW 5 (R 2) at an
# odd width, SW 3 at full width, SW 7 without idle cycles, and the paper configuration.
sm_rtl_test(NAME tb_edge_flag TOP sm_edge_flag SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_edge_flag.cpp
            PARAMS MAX_WIDTH=64 ROWS=2 COLS=8 ARGS --width 37 --rows 7 --frames 4)
sm_rtl_test(NAME tb_edge_flag_sw3 TOP sm_edge_flag SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_edge_flag.cpp
            PARAMS MAX_WIDTH=50 ROWS=1 COLS=7 ARGS --width 50 --rows 5 --frames 3 --seed 3)
sm_rtl_test(NAME tb_edge_flag_sw7 TOP sm_edge_flag SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_edge_flag.cpp
            PARAMS MAX_WIDTH=50 ROWS=3 COLS=9 ARGS --width 23 --rows 9 --frames 3 --seed 5 --idle 0)
sm_rtl_test(NAME tb_edge_flag_paper TOP sm_edge_flag SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_edge_flag.cpp
            PARAMS MAX_WIDTH=320 ROWS=2 COLS=8 ARGS --width 320 --rows 5 --frames 3 --seed 9)

# Output-stage evidence (m_matched, m_gap, m_fill_bg): every test above also compares it;
# these runs add cost kinds 3 (occ 0: lines with no match, runs at x = 0 and at the line
# end) and 4 (the largest gaps, DISP - 3 .. DISP - 1; tb_dp.cpp) and fail unless every
# case of the read-out was compared and the largest gap reached --min-gap
# (--require-cases), in the parallel, odd, folded and paper configurations.
sm_rtl_test(NAME tb_dp_runs RUN tb_dp
            ARGS --width 37 --rows 8 --frames 4 --kinds 34 --seed 21 --require-cases --min-gap 13)
sm_rtl_test(NAME tb_dp_runs_wmin RUN tb_dp ARGS --width 11 --rows 8 --frames 3 --kinds 30 --seed 22 --require-cases)
sm_rtl_test(NAME tb_dp_odd_runs RUN tb_dp_odd
            ARGS --width 50 --rows 8 --frames 4 --kinds 34 --seed 23 --require-cases --min-gap 7)
sm_rtl_test(NAME tb_dp_pu8_runs RUN tb_dp_pu8
            ARGS --width 64 --rows 8 --frames 4 --kinds 34 --seed 24 --require-cases --min-gap 13)
sm_rtl_test(NAME tb_dp_pu2_runs RUN tb_dp_pu2 ARGS --width 11 --rows 8 --frames 3 --kinds 3 --seed 25 --require-cases)
sm_rtl_test(NAME tb_dp_odd_pu2_runs RUN tb_dp_odd_pu2
            ARGS --width 23 --rows 8 --frames 4 --kinds 34 --seed 26 --require-cases --min-gap 7)
sm_rtl_test(NAME tb_dp_pu6_runs RUN tb_dp_pu6
            ARGS --width 31 --rows 8 --frames 4 --kinds 34 --seed 27 --require-cases --min-gap 9)
sm_rtl_test(NAME tb_dp_paper_runs RUN tb_dp_paper
            ARGS --width 320 --rows 6 --frames 4 --kinds 34 --seed 28 --require-cases --min-gap 125 LABELS "rtl;slow")
sm_rtl_test(NAME tb_dp_zynq8_runs RUN tb_dp_zynq8
            ARGS --width 200 --rows 6 --frames 4 --kinds 34 --seed 29 --require-cases --min-gap 125 LABELS "rtl;slow")
# The widest level count (DISP 254: 8-bit levels; kind 4 makes gaps of 251..253, the cap is
# 254), folded to 2 lanes (F 127) so that it builds and runs in seconds.
sm_rtl_test(NAME tb_dp_d254 TOP sm_dp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_dp.cpp
            PARAMS MAX_WIDTH=320 DISP=254 CW=6 PU=2
            ARGS --width 300 --rows 6 --frames 4 --kinds 3404 --seed 30 --require-cases --min-gap 251)

# The folded blocks' sub-step counter (sm_fold_step): counting up (sm_dp, sm_wta) and
# down (sm_right_wta), F a power of two or not, the smallest F and the paper's zynq F.
sm_rtl_test(NAME tb_fold_step TOP sm_fold_step SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_fold_step.cpp PARAMS F=2)
sm_rtl_test(NAME tb_fold_step_f5_down TOP sm_fold_step SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_fold_step.cpp
            PARAMS F=5 DOWN=1 ARGS --seed 2)
sm_rtl_test(NAME tb_fold_step_f16 TOP sm_fold_step SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_fold_step.cpp
            PARAMS F=16 ARGS --seed 3)
sm_rtl_test(NAME tb_fold_step_f16_down TOP sm_fold_step SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_fold_step.cpp
            PARAMS F=16 DOWN=1 ARGS --seed 4)
