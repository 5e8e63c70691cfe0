# Host interface and stream edges: register file, input sequencer, output formatter,
# plus the register-map unit test. Small configurations for speed, one paper point each.
set(SM_HOST_TESTS ${CMAKE_SOURCE_DIR}/tests)

function(sm_host_test name top src)
  sm_rtl_test(NAME ${name} TOP ${top} SOURCES ${SM_HOST_TESTS}/${src} ${ARGN})
  add_dependencies(${name} sm_regmap_gen_files)
endfunction()
sm_host_test(tb_axil_regs sm_axil_regs tb_axil_regs.cpp
             PARAMS MAX_WIDTH=64 MAX_HEIGHT=48 DISP=16 MAX_OBJECTS=4)
sm_host_test(tb_axil_regs_paper sm_axil_regs tb_axil_regs.cpp
             PARAMS MAX_WIDTH=320 MAX_HEIGHT=240 DISP=128 MAX_OBJECTS=8 LABELS rtl slow)
# with a speckle stage: the checked rules reset into its speckle mode
sm_host_test(tb_axil_regs_speckle sm_axil_regs tb_axil_regs.cpp
             PARAMS MAX_WIDTH=64 MAX_HEIGHT=48 DISP=16 MAX_OBJECTS=4 SPECKLE_ROWS=4)
sm_host_test(tb_seq sm_seq tb_seq.cpp PARAMS MAX_WIDTH=64 MAX_HEIGHT=48 FLUSH_ROWS=3)
sm_host_test(tb_seq_paper sm_seq tb_seq.cpp PARAMS MAX_WIDTH=320 MAX_HEIGHT=240 FLUSH_ROWS=28
             ARGS --paper LABELS rtl slow)
sm_host_test(tb_outfmt sm_outfmt tb_outfmt.cpp PARAMS MAX_WIDTH=64 FIFO_DEPTH=8)
sm_host_test(tb_outfmt_paper sm_outfmt tb_outfmt.cpp PARAMS MAX_WIDTH=320 FIFO_DEPTH=256
             ARGS --paper LABELS rtl slow)

# Register map against independent truth: sm::Regs defaults, the spec's grid size, layout.
# SM_ZYNQ_PU: the one configuration choice a user may make at configure time (the named
# configurations are otherwise written out in the test).
sm_unit_test(test_regmap LIBS sm_model INCLUDES ${SM_GEN_DIR} ${SM_HOST_TESTS}/common
             DEFINES SM_RTL_DIR="${SM_RTL_DIR}" SM_ZYNQ_PU=${SM_ZYNQ_PU} DEPENDS sm_regmap_gen_files)

# The sequencer's framing rules (model/seq.hpp) against hand-written streams; the fault
# classes' bit order against the register map.
sm_unit_test(test_seq_model LIBS sm_model INCLUDES ${SM_GEN_DIR} DEPENDS sm_regmap_gen_files DISCOVER)
