# Census transform, matching cost, line buffer and the shared window controller.

# sm_win_ctrl at two parameter points (square window with a column delay; rows only).
sm_rtl_test(NAME tb_win_ctrl_3x3 TOP sm_win_ctrl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_win_ctrl.cpp
            PARAMS MAX_WIDTH=64 D_ROWS=3 D_COLS=3 R_UP=3 R_DN=3 R_L=3 R_R=3)
sm_rtl_test(NAME tb_win_ctrl_rows TOP sm_win_ctrl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_win_ctrl.cpp
            PARAMS MAX_WIDTH=64 D_ROWS=4 D_COLS=0 R_UP=3 R_DN=3 R_L=0 R_R=0)

# The census border clamp along one window line: every inside run, the 3x3 and 7x7
# windows of the small tests and the paper's 15x15.
foreach(n 3 7 15)
  sm_rtl_test(NAME tb_edge_clamp_${n} TOP sm_edge_clamp SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_edge_clamp.cpp
              PARAMS N=${n})
endforeach()

# Census and cost at a small point, width 37 (odd, below MAX_WIDTH).
sm_rtl_test(NAME tb_census TOP sm_census SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_census.cpp
            PARAMS MAX_WIDTH=64 CENSUS=7)
sm_rtl_test(NAME tb_census_3 TOP sm_census SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_census.cpp
            PARAMS MAX_WIDTH=64 CENSUS=3)
sm_rtl_test(NAME tb_cost TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 ARGS --max-cost-frame)

# Paper configuration, few rows, odd width below MAX_WIDTH.
sm_rtl_test(NAME tb_census_paper TOP sm_census SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_census.cpp
            PARAMS MAX_WIDTH=320 CENSUS=15 ARGS --width 301 --heights 20 2 7 LABELS rtl slow)
sm_rtl_test(NAME tb_cost_paper TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CENSUS=15 ARGS --width 301 --heights 20 3 5 --max-cost-frame LABELS rtl slow)

# The cost's intensity term (sm_ad_term), every pixel pair: the default, no shift with the
# widest cap, the widest shift with a cap of 1, one the shifted difference never reaches,
# and a cap that is not all ones (5 at shift 3).
sm_rtl_test(NAME tb_ad_term TOP sm_ad_term SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_ad_term.cpp
            PARAMS L=3 AD_SHIFT=2 AD_MAX=7)
sm_rtl_test(NAME tb_ad_term_wide TOP sm_ad_term SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_ad_term.cpp
            PARAMS L=2 AD_SHIFT=0 AD_MAX=15)
sm_rtl_test(NAME tb_ad_term_narrow TOP sm_ad_term SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_ad_term.cpp
            PARAMS L=1 AD_SHIFT=7 AD_MAX=1)
sm_rtl_test(NAME tb_ad_term_uncapped TOP sm_ad_term SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_ad_term.cpp
            PARAMS L=1 AD_SHIFT=7 AD_MAX=15)
sm_rtl_test(NAME tb_ad_term_odd_cap TOP sm_ad_term SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_ad_term.cpp
            PARAMS L=2 AD_SHIFT=3 AD_MAX=5)
# Count plus term, capped (sm_cost_addsat): the paper (CB 224 in 8 bits, a cap below 2^HW - 1),
# a term wider than the count (CENSUS 3: CB 8 in 4 bits, 7 << 2 = 28), CB = 2^HW - 1 unshifted,
# and three dropped planes under a cap of 48 >> 3 = 6.
sm_rtl_test(NAME tb_cost_addsat TOP sm_cost_addsat SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost_addsat.cpp
            PARAMS L=128 HW=8 TW=3 COST_SHIFT=2 CB=224)
sm_rtl_test(NAME tb_cost_addsat_small TOP sm_cost_addsat SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost_addsat.cpp
            PARAMS L=5 HW=4 TW=3 COST_SHIFT=2 CB=8)
sm_rtl_test(NAME tb_cost_addsat_full TOP sm_cost_addsat SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost_addsat.cpp
            PARAMS L=7 HW=6 TW=4 COST_SHIFT=0 CB=63)
sm_rtl_test(NAME tb_cost_addsat_shift3 TOP sm_cost_addsat SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost_addsat.cpp
            PARAMS L=9 HW=6 TW=4 COST_SHIFT=3 CB=48)

# The census-only cost (AD_MAX 0: no intensity term), unfolded and folded.
sm_rtl_test(NAME tb_cost_census_only TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 AD_MAX=0 ARGS --max-cost-frame)
sm_rtl_test(NAME tb_cost_census_only_pu4 TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 PU=4 AD_MAX=0 ARGS --max-cost-frame)
# A cost shift the term's cap meets early (COST_SHIFT 4: 7 << 4 = 112 against CB 48).
sm_rtl_test(NAME tb_cost_shift4 TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 COST_SHIFT=4 ARGS --max-cost-frame)

# Folded sm_cost (F = DISP / PU clocks per beat, ce at most every F clocks, inputs held):
# PU = DISP explicitly (the parallel branch), F = 2 (the early-ce hold multiplexer), 4, 8
# and 16 (PU 1); F = 3 and F = 13 (segments whose depth is not a power of two, odd width
# and level count); the zynq point at PU 16 and 8.
foreach(pu 16 8 4 2 1)
  sm_rtl_test(NAME tb_cost_pu${pu} TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
              PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 PU=${pu} ARGS --max-cost-frame)
endforeach()
sm_rtl_test(NAME tb_cost_odd_pu4 TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=48 DISP=12 CENSUS=5 PU=4 ARGS --max-cost-frame)
sm_rtl_test(NAME tb_cost_odd_pu1 TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=48 DISP=13 CENSUS=5 PU=1 ARGS --max-cost-frame)
# Verilator's DFG peephole pass spends 37 of its 41 s on sm_cost at PU 16 (the 16
# popcount trees of 224 bits; 3 s without it, and 6.6 MB of C++ instead of 9.7 MB); the
# product models (sim/sim.cmake) keep it.
foreach(pu 16 8)
  sm_rtl_test(NAME tb_cost_zynq_pu${pu} TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
              PARAMS MAX_WIDTH=320 DISP=128 CENSUS=15 PU=${pu} ARGS --width 301 --heights 20 3 5 --max-cost-frame
              LABELS rtl slow VERILATOR_ARGS -fno-dfg-peephole)
endforeach()

# Model unit tests.
sm_unit_test(test_census_model LIBS sm_model ${OpenCV_LIBS} TIMEOUT 120)
# Again with the AVX-512 Hamming kernel switched off, so that the AVX2 (or portable)
# kernel is tested on a machine that has AVX-512 too.
add_test(NAME test_census_model_no_avx512 COMMAND test_census_model)
set_tests_properties(test_census_model_no_avx512 PROPERTIES LABELS unit TIMEOUT 120 ENVIRONMENT SM_NO_AVX512=1)

# The bit-plane to lane-order transpose on its own: padded planes and lanes, two plane
# blocks, the paper configuration's 8 x 128, the degenerate 1 x 1, and 128 x 8 (lanes to
# planes: the aggregator's input, the paper configuration's costs).
foreach(cfg "6;13" "8;128" "10;5" "1;1" "128;8")
  list(GET cfg 0 p)
  list(GET cfg 1 l)
  sm_rtl_test(NAME tb_plane2lane_${p}x${l} TOP sm_plane2lane SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_plane2lane.cpp
              PARAMS P=${p} L=${l})
endforeach()
# The compressor heap on its own (H0 as a hex literal, column 0 last): the aggregation's
# 25 weighted costs, the paper popcount's leaves, no stage at all, and uneven columns.
function(sm_bitheap_test name nc l)
  set(hex "")
  foreach(h ${ARGN})
    math(EXPR v "${h}" OUTPUT_FORMAT HEXADECIMAL)
    string(SUBSTRING "${v}" 2 -1 v)
    string(LENGTH "${v}" n)
    while(n LESS 8)
      string(PREPEND v "0")
      math(EXPR n "${n} + 1")
    endwhile()
    string(PREPEND hex "${v}")
  endforeach()
  math(EXPR bits "${nc} * 32")
  sm_rtl_test(NAME tb_bitheap_${name} TOP sm_bitheap SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_bitheap.cpp
              PARAMS NC=${nc} L=${l} "H0=${bits}'h${hex}" ARGS --heights ${ARGN})
endfunction()
sm_bitheap_test(agg 13 128 25 25 25 25 25 25 25 25 0 0 0 0 0)
sm_bitheap_test(pop 8 5 75 75 0 0 0 0 0 0)
sm_bitheap_test(none 2 3 1 1)
sm_bitheap_test(uneven 6 1 7 0 4 2 1 0)

# sm_cost with a level count that is not a multiple of 8 (padded lanes in the transpose)
sm_rtl_test(NAME tb_cost_odd TOP sm_cost SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_cost.cpp
            PARAMS MAX_WIDTH=48 DISP=13 CENSUS=5 ARGS --max-cost-frame)
