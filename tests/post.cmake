# Post-processing (docs/algorithm.md sections 7-8): model unit tests and block tests.
sm_unit_test(test_post_model LIBS sm_model ${OpenCV_LIBS} INCLUDES ${OpenCV_INCLUDE_DIRS} DISCOVER)

# The three median filters are sm_post_median at the window shapes sm_top gives them.
set(_shape_vmed RY=2 RX=0)
set(_shape_med3 RY=1 RX=1)
set(_shape_med53 RY=2 RX=1)
foreach(_f vmed med3 med53)
  sm_rtl_test(NAME tb_post_${_f} TOP sm_post_median SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_post_filter.cpp
              PARAMS MAX_WIDTH=64 DISP=16 ${_shape_${_f}} ARGS --filter ${_f} --width 37 --height 9)
  sm_rtl_test(NAME tb_post_${_f}_paper TOP sm_post_median SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_post_filter.cpp
              PARAMS MAX_WIDTH=320 DISP=128 ${_shape_${_f}} ARGS --filter ${_f} --width 320 --height 6
              LABELS "rtl;slow")
endforeach()

sm_rtl_test(NAME tb_objects TOP sm_objects SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_objects.cpp
            PARAMS MAX_WIDTH=64 MAX_HEIGHT=64 DISP=16 MAX_OBJECTS=4 LABEL_SLOTS=16
            ARGS --width 37 --height 23)
sm_rtl_test(NAME tb_objects_paper TOP sm_objects SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_objects.cpp
            PARAMS MAX_WIDTH=320 MAX_HEIGHT=240 DISP=128 MAX_OBJECTS=8 LABEL_SLOTS=64
            ARGS --width 320 --height 40 LABELS "rtl;slow")
# The whole paper frame: coordinates, counts and sums up to their widest values.
sm_rtl_test(NAME tb_objects_paper_full RUN tb_objects_paper ARGS --width 320 --height 240 LABELS "rtl;slow")
# LABEL_SLOTS not a power of two: the label banks sit at an offset, not behind a bank bit.
sm_rtl_test(NAME tb_objects_slots12 TOP sm_objects SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_objects.cpp
            PARAMS MAX_WIDTH=64 MAX_HEIGHT=64 DISP=16 MAX_OBJECTS=4 LABEL_SLOTS=12
            ARGS --width 41 --height 19)

# More labels than Verilator unrolls a loop over (64): the table's per-entry update.
sm_rtl_test(NAME tb_objects_slots100 TOP sm_objects SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_objects.cpp
            PARAMS MAX_WIDTH=320 MAX_HEIGHT=64 DISP=16 MAX_OBJECTS=8 LABEL_SLOTS=100
            ARGS --width 301 --height 29)

# MAX_OBJECTS not a power of two: the list banks keep unused entries.
sm_rtl_test(NAME tb_objects_obj3 TOP sm_objects SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_objects.cpp
            PARAMS MAX_WIDTH=64 MAX_HEIGHT=64 DISP=16 MAX_OBJECTS=3 LABEL_SLOTS=16
            ARGS --width 33 --height 21)

# The labeller's lowest-free search (sm_lowest_set): one, two and three tiers of 8.
foreach(_n 8 64 12 1 200 512)
  if(_n LESS_EQUAL 1)
    set(_iw 1)
  else()
    math(EXPR _m "${_n} - 1")
    set(_iw 0)
    while(_m GREATER 0)
      math(EXPR _m "${_m} >> 1")
      math(EXPR _iw "${_iw} + 1")
    endwhile()
  endif()
  sm_rtl_test(NAME tb_lowest_set_${_n} TOP sm_lowest_set SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_lowest_set.cpp
              PARAMS N=${_n} IW=${_iw})
endforeach()

# Band filter F0 (sm_post_band) against the model's post_band: odd and tiny widths one
# after the other without a reset, frames of at most K rows among them.
sm_rtl_test(NAME tb_post_band TOP sm_post_band SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_post_band.cpp
            PARAMS MAX_WIDTH=64 DISP=16 K=3 ARGS --widths 37,2,5,64 --height 9)
sm_rtl_test(NAME tb_post_band_k8 TOP sm_post_band SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_post_band.cpp
            PARAMS MAX_WIDTH=64 DISP=16 K=8 ARGS --widths 23,64,3 --height 13)
sm_rtl_test(NAME tb_post_band_paper TOP sm_post_band SOURCES ${CMAKE_CURRENT_LIST_DIR}/tb_post_band.cpp
            PARAMS MAX_WIDTH=320 DISP=128 K=8 ARGS --widths 319,320,17 --height 20 LABELS "rtl;slow")
