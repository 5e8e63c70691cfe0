# Output stage (docs/algorithm.md section 9: sub-pixel, validity, confidence): model tests.
sm_unit_test(test_output_model LIBS sm_toolio INCLUDES ${CMAKE_SOURCE_DIR}/tests/common DISCOVER)

# The output word after the post filters (sm_outword) against the model's out_word: DISP 16
# at odd widths, DISP 10 (not a power of two), the paper's DISP 128 at its width and at one
# narrower than DISP (every column then meets the left-border rule).
sm_rtl_test(NAME tb_outword TOP sm_outword SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_outword.cpp
            PARAMS MAX_WIDTH=64 DISP=16 ARGS --widths 37,2,64 --height 9)
sm_rtl_test(NAME tb_outword_odd TOP sm_outword SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_outword.cpp
            PARAMS MAX_WIDTH=50 DISP=10 ARGS --widths 23,3 --height 7)
sm_rtl_test(NAME tb_outword_paper TOP sm_outword SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_outword.cpp
            PARAMS MAX_WIDTH=320 DISP=128 ARGS --widths 320,67 --height 6)

# The output stage's row store (sm_line_store): reader lags of one row to LINES - 1 rows,
# a width below MAX_WIDTH (rows do not fill their stride) and a non-power-of-two depth.
sm_rtl_test(NAME tb_line_store TOP sm_line_store SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_line_store.cpp
            PARAMS DATA_W=13 MAX_WIDTH=40 LINES=3 ARGS --width 37 --rows 11 --lags 37,50,74)
sm_rtl_test(NAME tb_line_store_deep RUN tb_line_store ARGS --width 40 --rows 9 --lags 40,79,80)
sm_rtl_test(NAME tb_line_store_16 TOP sm_line_store SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_line_store.cpp
            PARAMS DATA_W=30 MAX_WIDTH=64 LINES=16 ARGS --width 23 --rows 40 --lags 23,200,345)

# The output stage's first half (sm_outfields) against the model's out_fields: DISP 16 and
# CW 4, DISP 10 and CW 3 (neither a power of two), the paper's DISP 128 and CW 6.
sm_rtl_test(NAME tb_outfields TOP sm_outfields SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_outfields.cpp
            PARAMS MAX_WIDTH=64 DISP=16 CW=4 ARGS --width 37 --height 40)
sm_rtl_test(NAME tb_outfields_odd TOP sm_outfields SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_outfields.cpp
            PARAMS MAX_WIDTH=50 DISP=10 CW=3 ARGS --width 23 --height 30)
sm_rtl_test(NAME tb_outfields_paper TOP sm_outfields SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_outfields.cpp
            PARAMS MAX_WIDTH=320 DISP=128 CW=6 ARGS --width 320 --height 5)

# The bound study's features (known answers on small frames) and its leave-one-scene-out
# forest (it must learn a rule the frames share).
if(TARGET sm_output_bound)
  sm_unit_test(test_output_bound LIBS sm_output_bound DISCOVER)
endif()

# The output words' smoothing (sm_out_smooth) against the model's smooth_output: DISP 16 at
# odd and tiny widths, DISP 10 (not a power of two), the paper's DISP 128 at its width.
sm_rtl_test(NAME tb_out_smooth TOP sm_out_smooth SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_out_smooth.cpp
            PARAMS MAX_WIDTH=64 DISP=16 ARGS --widths 37,3,64 --height 9)
sm_rtl_test(NAME tb_out_smooth_odd TOP sm_out_smooth SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_out_smooth.cpp
            PARAMS MAX_WIDTH=50 DISP=10 ARGS --widths 23,4 --height 7)
sm_rtl_test(NAME tb_out_smooth_paper TOP sm_out_smooth SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_out_smooth.cpp
            PARAMS MAX_WIDTH=320 DISP=128 ARGS --widths 320,67 --height 6)
sm_unit_test(test_smooth_model LIBS sm_model DISCOVER)
# The row support of the confidence (sm_out_support) against the model's
# row_support_output: DISP 16 at odd widths, rows shorter than the samples' reach too,
# DISP 10, the paper's DISP 128 at its width.
sm_rtl_test(NAME tb_out_support TOP sm_out_support SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_out_support.cpp
            PARAMS DISP=16 ARGS --widths 37,16,64,5 --height 9)
sm_rtl_test(NAME tb_out_support_odd TOP sm_out_support SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_out_support.cpp
            PARAMS DISP=10 ARGS --widths 23,17,3 --height 7)
sm_rtl_test(NAME tb_out_support_paper TOP sm_out_support SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_out_support.cpp
            PARAMS DISP=128 ARGS --widths 320,67 --height 6)

# The speckle stage (sm_speckle) against the model's SpeckleStage, beat by beat: tables
# small enough to fill (KEEP), a table of a size not a power of two, one held row, queues
# of 2..16 beats (ce held while the labeller is behind), the folded pacing, and the zynq
# configuration's sizes.
sm_rtl_test(NAME tb_speckle TOP sm_speckle SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_speckle.cpp
            PARAMS MAX_WIDTH=40 ROWS=3 LABELS=16 SLACK=4 ARGS --widths 37,5,40 --height 11 --frames 7)
sm_rtl_test(NAME tb_speckle_odd TOP sm_speckle SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_speckle.cpp
            PARAMS MAX_WIDTH=23 ROWS=1 LABELS=6 SLACK=2 ARGS --widths 23,2 --height 9 --frames 6 --idle 50)
sm_rtl_test(NAME tb_speckle_two TOP sm_speckle SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_speckle.cpp
            PARAMS MAX_WIDTH=16 ROWS=7 LABELS=2 SLACK=8 ARGS --widths 16,9 --height 13 --frames 6 --gap 16)
sm_rtl_test(NAME tb_speckle_zynq TOP sm_speckle SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_speckle.cpp
            PARAMS MAX_WIDTH=320 ROWS=32 LABELS=1024 SLACK=16 ARGS --widths 320,67 --height 40 --frames 7 --gap 16 --idle 5)
# A bench's list with an empty item is refused (CLI11 alone would drop the item and test
# fewer widths): toolio/sm_cli.hpp's check_delimited, as in every tool.
add_test(NAME tb_speckle_bad_widths COMMAND tb_speckle --widths 37,,40)
set_tests_properties(tb_speckle_bad_widths PROPERTIES LABELS robust
                     PASS_REGULAR_EXPRESSION "--widths: '37,,40': an empty item in a ','-separated list")

# The output study's speckle check against OpenCV's filterSpeckles and a streaming known answer.
if(TARGET sm_speckle)
  sm_unit_test(test_speckle LIBS sm_speckle opencv_calib3d DISCOVER)
  # The host's check (toolio) against that union-find and known answers.
  sm_unit_test(test_host_speckle LIBS sm_speckle sm_toolio DISCOVER)
endif()
# The trellis's min-marginals (sm_output_study --study dp-margin) against every path of tiny
# lines and the model's trellis.
if(TARGET sm_dp_margin)
  sm_unit_test(test_dp_margin LIBS sm_dp_margin sm_model DISCOVER)
endif()
# The window supports of sm_output_study --study window-conf: known answers, brute force.
if(TARGET sm_window_support)
  sm_unit_test(test_window_support LIBS sm_window_support DISCOVER)
endif()
