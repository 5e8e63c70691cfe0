# Support-weight aggregation (docs/algorithm.md section 5): model unit tests and block tests.
sm_unit_test(test_aggregate_model LIBS sm_model ${OpenCV_LIBS} INCLUDES ${OpenCV_INCLUDE_DIRS} DISCOVER)
# Again with the AVX-512 kernels switched off (the AVX2 or portable aggregation is then
# tested on a machine that has AVX-512 too).
add_test(NAME test_aggregate_model_no_avx512 COMMAND test_aggregate_model)
set_tests_properties(test_aggregate_model_no_avx512 PROPERTIES LABELS unit ENVIRONMENT SM_NO_AVX512=1)

# Block tests: odd width 37, three frames back to back, 30 % idle cycles, then a frame of
# raw costs all at the port's maximum (--max-cost-frame).
set(_agg_tb ${CMAKE_CURRENT_LIST_DIR}/tb_sw_aggregate.cpp)
sm_rtl_test(NAME tb_sw_aggregate_sw3 TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 SW=3 COST_SHIFT=2
            ARGS --width 37 --heights 9 6 11 --max-cost-frame)
sm_rtl_test(NAME tb_sw_aggregate_sw5 TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=7 SW=5 COST_SHIFT=1
            ARGS --width 37 --heights 9 4 11 --seed 2 --max-cost-frame)
sm_rtl_test(NAME tb_sw_aggregate_paper TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=320 DISP=128 CENSUS=15 SW=5 COST_SHIFT=2
            ARGS --width 317 --heights 6 5 --seed 3 --max-cost-frame LABELS "rtl;slow")
# A cost width of 6 at a small point (CENSUS 11, COST_SHIFT 1: costs up to 60, the port's
# maximum 63): the max-cost frame's windows whose normalised cost rounds above 63 saturate.
sm_rtl_test(NAME tb_sw_aggregate_sat TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=64 DISP=16 CENSUS=11 SW=5 COST_SHIFT=1
            ARGS --width 41 --heights 9 7 --seed 21 --max-cost-frame)
# Folded datapath (PU < DISP, F = DISP / PU clocks per beat, issue 20): DISP 16 at
# PU 16 (F 1, the parallel branch named explicitly), 8, 4, 2 and 1, a non-power-of-two
# F (DISP 12, PU 4), SW 3, 5 and 7, odd widths, random ce gaps on top of the pacing;
# MAX_WIDTH 50 (not a power of two: the cost line buffer in two banks, sm_sw_foldlb
# g_two, at a power-of-two F and at F 3).
# Fields: name; SW; DISP; PU; COST_SHIFT; active width; seed; MAX_WIDTH.
foreach(_p "sw5_pu16;5;16;16;1;37;2;64" "sw5_pu8;5;16;8;1;37;5;64" "sw3_pu4;3;16;4;2;37;6;64"
           "sw5_pu2;5;16;2;1;23;7;64" "sw3_pu1;3;16;1;2;19;8;64" "sw7_pu4;7;16;4;1;29;9;64"
           "sw5_d12_pu4;5;12;4;2;31;10;64" "w50_pu4;5;16;4;1;50;14;50" "w50_d12_pu4;5;12;4;2;47;15;50")
  list(GET _p 0 _n)
  list(GET _p 1 _sw)
  list(GET _p 2 _d)
  list(GET _p 3 _pu)
  list(GET _p 4 _cs)
  list(GET _p 5 _w)
  list(GET _p 6 _seed)
  list(GET _p 7 _mw)
  sm_rtl_test(NAME tb_sw_aggregate_${_n} TOP sm_sw_aggregate SOURCES ${_agg_tb}
              PARAMS MAX_WIDTH=${_mw} DISP=${_d} CENSUS=7 SW=${_sw} COST_SHIFT=${_cs} PU=${_pu}
              ARGS --width ${_w} --heights 9 4 11 --seed ${_seed} --max-cost-frame)
endforeach()
# The folded window alone (sm_sw_foldwin) against its definition: banks of the group's
# width and narrower (the last one short), F a power of two and not, N 1 .. 4 (N = 1 is
# legal but unused: the aggregation's N is SW - 1 >= 2), and the zynq point's group of 240
# bits in 64-bit banks.
# Fields: name; W; N; F; BANK_W.
foreach(_p "n1_f2;37;1;2;64" "n2_f3_b16;37;2;3;16" "n3_f5_b30;100;3;5;30" "n4_f8;60;4;8;64"
           "zynq;240;4;16;64")
  list(GET _p 0 _n)
  list(GET _p 1 _w)
  list(GET _p 2 _nn)
  list(GET _p 3 _f)
  list(GET _p 4 _b)
  sm_rtl_test(NAME tb_sw_foldwin_${_n} TOP sm_sw_foldwin SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_sw_foldwin.cpp
              PARAMS W=${_w} N=${_nn} F=${_f} BANK_W=${_b})
endforeach()
# The zynq point (320 wide, DISP 128, CENSUS 15, SW 5) at PU 16 and 8, the full line
# with 50 % idle on the PU 16 binary.
sm_rtl_test(NAME tb_sw_aggregate_zynq_pu16 TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=320 DISP=128 CENSUS=15 SW=5 COST_SHIFT=2 PU=16
            ARGS --width 317 --heights 6 5 --seed 11 --max-cost-frame LABELS "rtl;slow")
sm_rtl_test(NAME tb_sw_aggregate_zynq_pu8 TOP sm_sw_aggregate SOURCES ${_agg_tb}
            PARAMS MAX_WIDTH=320 DISP=128 CENSUS=15 SW=5 COST_SHIFT=2 PU=8
            ARGS --width 317 --heights 6 5 --seed 12 --max-cost-frame LABELS "rtl;slow")
sm_rtl_test(NAME tb_sw_aggregate_zynq_pu16_w320 RUN tb_sw_aggregate_zynq_pu16
            ARGS --width 320 --heights 7 6 --seed 13 --idle 50 LABELS "rtl;slow")
# Full MAX_WIDTH line (last column of the line buffer) with the paper-point binary.
sm_rtl_test(NAME tb_sw_aggregate_paper_w320 RUN tb_sw_aggregate_paper
            ARGS --width 320 --heights 7 6 --seed 4 --idle 50 LABELS "rtl;slow")
