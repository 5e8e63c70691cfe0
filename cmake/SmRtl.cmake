# Helpers to verilate RTL blocks for tests and tools.
#
# sm_verilated(TARGET <exe> TOP <module> [PARAMS NAME=VALUE ...] [TRACE] [THREADS n]
#              [OPT_FAST flags...] [OPT_SLOW flags...])
#   Verilates rtl/<module>.v (submodules are found in rtl/ and the generated folder)
#   into the executable target. The target gets SM_VTOP / SM_VTOP_H naming the model
#   class and header, and SM_P_<NAME>=<VALUE> for every parameter. OPT_FAST / OPT_SLOW
#   are extra compiler flags for the generated files Verilator marks as run every
#   cycle / run once (construction, initial blocks, trace declarations). With
#   -DSM_COVERAGE=ON the model has line and toggle coverage and the target (and its
#   users) get SM_COVERAGE=1 (tests/common/sm_coverage.hpp).
#
# verilate() lists the generated C++ files when CMake configures, and runs Verilator
# again at configure time only when its command line changes. An RTL edit that changes
# how many files Verilator writes would leave a build compiling stale files. So every
# RTL file is a configure dependency and a digest of the RTL is part of the command
# line: an RTL edit re-configures, and the file lists are taken afresh.
file(GLOB SM_RTL_FILES CONFIGURE_DEPENDS ${SM_RTL_DIR}/*.v ${SM_RTL_DIR}/*.vh
     ${SM_RTL_DIR}/*.json)
set(_sm_rtl_md5 "")
foreach(f ${SM_RTL_FILES})
  file(MD5 ${f} _m)
  string(APPEND _sm_rtl_md5 ${_m})
endforeach()
string(MD5 SM_RTL_DIGEST "${_sm_rtl_md5}")
set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${SM_RTL_FILES})
set(SM_VERILATOR_ARGS --x-assign fast --x-initial fast -O3 --assert -Wno-fatal
    -y ${SM_RTL_DIR} -y ${SM_GEN_DIR} -I${SM_GEN_DIR} +define+SM_RTL_DIGEST=${SM_RTL_DIGEST})
# sm_param_flags(<args var> <defs var> NAME=VALUE ...): appends -GNAME=VALUE to the
# Verilator arguments and SM_P_NAME=VALUE to the compile definitions, for each parameter.
function(sm_param_flags args_var defs_var)
  set(a ${${args_var}})
  set(d ${${defs_var}})
  foreach(p ${ARGN})
    list(APPEND a -G${p})
    string(REPLACE "=" ";" kv ${p})
    list(GET kv 0 k)
    list(GET kv 1 v)
    list(APPEND d SM_P_${k}=${v})
  endforeach()
  set(${args_var} ${a} PARENT_SCOPE)
  set(${defs_var} ${d} PARENT_SCOPE)
endfunction()

function(sm_verilated)
  cmake_parse_arguments(V "TRACE" "TARGET;TOP;THREADS;TRACE_DEPTH" "PARAMS;OPT_FAST;OPT_SLOW"
                        ${ARGN})
  set(args ${SM_VERILATOR_ARGS})
  if(V_TRACE_DEPTH)
    list(APPEND args --trace-depth ${V_TRACE_DEPTH})
  endif()
  if(SM_COVERAGE)
    list(APPEND args --coverage-line --coverage-toggle)
  endif()
  set(defs SM_VTOP=V${V_TARGET} SM_VTOP_H="V${V_TARGET}.h")
  sm_param_flags(args defs ${V_PARAMS})
  set(extra)
  if(V_TRACE)
    list(APPEND extra TRACE)
  endif()
  if(V_THREADS)
    list(APPEND extra THREADS ${V_THREADS})
  endif()
  if(V_OPT_FAST)
    list(APPEND extra OPT_FAST ${V_OPT_FAST})
  endif()
  if(V_OPT_SLOW)
    list(APPEND extra OPT_SLOW ${V_OPT_SLOW})
  endif()
  verilate(${V_TARGET} SOURCES ${SM_RTL_DIR}/${V_TOP}.v TOP_MODULE ${V_TOP}
           PREFIX V${V_TARGET} VERILATOR_ARGS ${args} ${extra})
  target_compile_definitions(${V_TARGET} PRIVATE ${defs})
  if(SM_COVERAGE)
    # tests/common/sm_coverage.hpp writes the data; PUBLIC: also the users of a library
    target_compile_definitions(${V_TARGET} PUBLIC SM_COVERAGE=1)
  endif()
endfunction()

# sm_rtl_test(NAME <test> TOP <module> SOURCES <tb.cpp ...> [PARAMS ...] [LABELS ...]
#             [ARGS ...] [TRACE] [TIMEOUT s])
#   One Verilated block test at one parameter point, registered with ctest.
function(sm_rtl_test)
  cmake_parse_arguments(T "TRACE" "NAME;TOP;TIMEOUT" "SOURCES;PARAMS;LABELS;ARGS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_include_directories(${T_NAME} PRIVATE ${CMAKE_SOURCE_DIR}/tests/common
                                               ${CMAKE_SOURCE_DIR}/sim ${SM_GEN_DIR})
  target_link_libraries(${T_NAME} PRIVATE sm_model fmt::fmt)
  set(tr)
  if(T_TRACE)
    set(tr TRACE)
  endif()
  sm_verilated(TARGET ${T_NAME} TOP ${T_TOP} PARAMS ${T_PARAMS} ${tr})
  # Block tests run for seconds; their generated C++ (tens of MB at the paper point)
  # compiles several times faster at -O1 than at -O3.
  target_compile_options(${T_NAME} PRIVATE -O1)
  add_test(NAME ${T_NAME} COMMAND ${T_NAME} ${T_ARGS})
  if(NOT T_LABELS)
    set(T_LABELS rtl)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT})
endfunction()
