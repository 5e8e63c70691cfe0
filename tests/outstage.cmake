# Output stage arithmetic (docs/algorithm.md sections 9.1 and 9.3; issue 39): the sub-pixel
# fit (sm_subpix_fit) and the confidence's uniqueness ratio (sm_conf_ratio), both on the
# one divider sm_udiv, streamed with random ce gaps and compared with the model and with
# an independent float reference (tests/common/pipe_stream.hpp).

# Fit: every (cm, c0, cp, fit) at CW 6 (paper, 2^19 vectors), 4 (small) and 3 (odd), with
# and without idle cycles; 10^6 random vectors at CW 8 (and every one, slow).
sm_rtl_test(NAME tb_subpix_fit TOP sm_subpix_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_subpix_fit.cpp
            PARAMS CW=6)
sm_rtl_test(NAME tb_subpix_fit_noidle RUN tb_subpix_fit ARGS --idle 0 --seed 2)
sm_rtl_test(NAME tb_subpix_fit_cw4 TOP sm_subpix_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_subpix_fit.cpp
            PARAMS CW=4 ARGS --idle 60 --seed 3)
sm_rtl_test(NAME tb_subpix_fit_cw3 TOP sm_subpix_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_subpix_fit.cpp
            PARAMS CW=3 ARGS --seed 4)
sm_rtl_test(NAME tb_subpix_fit_cw8 TOP sm_subpix_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_subpix_fit.cpp
            PARAMS CW=8 ARGS --random 1000000 --seed 5)
sm_rtl_test(NAME tb_subpix_fit_cw8_all RUN tb_subpix_fit_cw8 ARGS --seed 6 LABELS "rtl;slow")

# Ratio: every (c1, c2), four passes in new orders, at CW 6 and 8; CW 4 and 3 without and
# with many idle cycles.
sm_rtl_test(NAME tb_conf_ratio TOP sm_conf_ratio SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_conf_ratio.cpp
            PARAMS CW=6)
sm_rtl_test(NAME tb_conf_ratio_cw8 TOP sm_conf_ratio SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_conf_ratio.cpp
            PARAMS CW=8 ARGS --seed 2)
sm_rtl_test(NAME tb_conf_ratio_cw4 TOP sm_conf_ratio SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_conf_ratio.cpp
            PARAMS CW=4 ARGS --idle 0 --passes 16 --seed 3)
sm_rtl_test(NAME tb_conf_ratio_cw3 TOP sm_conf_ratio SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_conf_ratio.cpp
            PARAMS CW=3 ARGS --idle 60 --passes 64 --seed 4)

# The narrowest costs (CW 1: 6-bit dividends, a 2-bit divisor in the ratio).
sm_rtl_test(NAME tb_subpix_fit_cw1 TOP sm_subpix_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_subpix_fit.cpp
            PARAMS CW=1 ARGS --seed 7)
sm_rtl_test(NAME tb_conf_ratio_cw1 TOP sm_conf_ratio SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_conf_ratio.cpp
            PARAMS CW=1 ARGS --passes 256 --seed 5)

# The divider on its own, every (n, d): the fit's shape at CW 6, the ratio's, a divisor
# wider than the dividend, the fewest quotient bits (tests/tb_udiv.cpp).
sm_rtl_test(NAME tb_udiv TOP sm_udiv SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_udiv.cpp PARAMS NW=11 DW=8 QW=4)
sm_rtl_test(NAME tb_udiv_q5 TOP sm_udiv SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_udiv.cpp PARAMS NW=11 DW=7 QW=5)
sm_rtl_test(NAME tb_udiv_wide_d TOP sm_udiv SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_udiv.cpp PARAMS NW=5 DW=9 QW=4)
sm_rtl_test(NAME tb_udiv_q2 TOP sm_udiv SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_udiv.cpp PARAMS NW=6 DW=3 QW=2
            ARGS --idle 0)
