# Synthesis check (label synth): every block that exists is mapped with Yosys
# synth_xilinx -family xc7 at the small configuration; a test fails on a Yosys error, on
# unmapped cells, or -- for the blocks in tools/synth/expect_bram.txt, mapped with
# -nolutram -- when no block RAM results. sm_top also regenerates the harness report
# build/synth/sm_top_stereo_sim_small.json.
set(SM_SYNTH_CI_PARAMS MAX_WIDTH=64 MAX_HEIGHT=48 DISP=16 CENSUS=7 SW=3 RECT_RADIUS=4)
file(STRINGS ${CMAKE_SOURCE_DIR}/tools/synth/expect_bram.txt bram_lines REGEX "^sm_")
set(SM_SYNTH_EXPECT_BRAM)
foreach(l ${bram_lines})
  string(REGEX MATCH "^[a-z0-9_]+" m "${l}")
  list(APPEND SM_SYNTH_EXPECT_BRAM ${m})
endforeach()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             ${CMAKE_SOURCE_DIR}/tools/synth/expect_bram.txt)

file(GLOB synth_rtl CONFIGURE_DEPENDS ${SM_RTL_DIR}/sm_*.v)
foreach(f ${synth_rtl})
  get_filename_component(m ${f} NAME_WE)
  set(args -t ${m} -f xc7 -x $<TARGET_FILE:sm_synth_report> -L ${SM_GEN_DIR} -T 1800)
  foreach(p ${SM_SYNTH_CI_PARAMS})
    list(APPEND args -p ${p})
  endforeach()
  set(labels synth)
  set(cost 10)
  if(m STREQUAL "sm_top")  # the whole IP again, as synth_small makes it (blocks mode)
    list(APPEND args -c stereo_sim_small -o ${CMAKE_BINARY_DIR}/synth -B)
    set(labels synth slow)
    set(cost 150)
  else()
    list(APPEND args -c ci -o ${CMAKE_BINARY_DIR}/synth/ci)
  endif()
  if(m IN_LIST SM_SYNTH_EXPECT_BRAM)
    list(APPEND args -n -b)
  endif()
  add_test(NAME synth_${m} COMMAND ${CMAKE_SOURCE_DIR}/tools/synth/sm_synth.sh ${args})
  # COST: a fresh build has no test times yet, and ctest -j starts the costly tests first
  # only when told (the whole-IP synthesis in blocks mode, ~4 min, last would be the suite's tail)
  set_tests_properties(synth_${m} PROPERTIES LABELS "${labels}" TIMEOUT 1900 COST ${cost})
endforeach()

# The folded datapath at the small configuration (PU 4: 4 clocks per pixel): the three
# folded blocks map too, and the aggregation's line buffer is still block RAM.
foreach(m sm_cost sm_sw_aggregate sm_dp)
  set(args -t ${m} -f xc7 -x $<TARGET_FILE:sm_synth_report> -L ${SM_GEN_DIR} -T 1800 -c ci_fold
      -o ${CMAKE_BINARY_DIR}/synth/ci)
  foreach(p ${SM_SYNTH_CI_PARAMS} PU=4)
    list(APPEND args -p ${p})
  endforeach()
  if(m IN_LIST SM_SYNTH_EXPECT_BRAM)
    list(APPEND args -n -b)
  endif()
  add_test(NAME synth_${m}_fold COMMAND ${CMAKE_SOURCE_DIR}/tools/synth/sm_synth.sh ${args})
  set_tests_properties(synth_${m}_fold PROPERTIES LABELS synth TIMEOUT 1900 COST 10)
endforeach()

# Place and route (family ecp5: synth_ecp5, then nextpnr-ecp5 from .venv) of one block
# with a line memory and register-to-register paths at the small configuration (10 s):
# the flow runs end to end and reports the clock it achieved.
# Without SM_VENV's nextpnr (scripts/deps.sh) the test is left out, as the Python ones are.
if(NOT EXISTS ${SM_NEXTPNR_ECP5})
  message(WARNING "${SM_NEXTPNR_ECP5} not found: no pnr_sm_post_band test (scripts/deps.sh installs it)")
else()
  set(args -t sm_post_band -f ecp5 -N ${SM_NEXTPNR_ECP5} -x $<TARGET_FILE:sm_synth_report>
      -L ${SM_GEN_DIR} -T 1800 -c ci -o ${CMAKE_BINARY_DIR}/synth/ci_ecp5)
  foreach(p ${SM_SYNTH_CI_PARAMS})
    list(APPEND args -p ${p})
  endforeach()
  add_test(NAME pnr_sm_post_band COMMAND ${CMAKE_SOURCE_DIR}/tools/synth/sm_synth.sh ${args})
  set_tests_properties(pnr_sm_post_band PROPERTIES LABELS synth TIMEOUT 1900 COST 10
                       PASS_REGULAR_EXPRESSION "Fmax [0-9]+\\.[0-9] MHz \\(target 100\\)")
endif()

# The flow's option checks stop it with one error line before any run: a bad nextpnr seed.
add_test(NAME synth_bad_seed
         COMMAND sh -c "out=$(\"$0\" -t sm_post_band -f ecp5 -N /bin/true -x \"$1\" -S 0 2>&1) && exit 1; \
echo \"$out\"; test \"$out\" = \"sm_synth: bad seed '0' (-S: a positive integer)\""
                 ${CMAKE_SOURCE_DIR}/tools/synth/sm_synth.sh $<TARGET_FILE:sm_synth_report>)
set_tests_properties(synth_bad_seed PROPERTIES LABELS robust TIMEOUT 60)
