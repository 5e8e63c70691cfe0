# Helpers to verilate RTL blocks for tests and tools.
#
# The build, not the configure step, runs Verilator: a configure takes seconds, an RTL
# edit re-Verilates only the models it feeds, and the Verilator runs overlap with the
# compiles of the rest. Verilator's output file names depend on the RTL, so
# cmake/SmVerilatorGroup.cmake groups them into fixed-name files the build knows in
# advance (see there). Every model links the one Verilator runtime below instead of
# compiling its own copy (it does not depend on the model's options).
file(GLOB SM_RTL_FILES CONFIGURE_DEPENDS ${SM_RTL_DIR}/*.v ${SM_RTL_DIR}/*.vh
     ${SM_RTL_DIR}/*.json)
set(SM_VERILATOR_ARGS --x-assign fast --x-initial fast -O3 --assert -Wno-fatal
    -y ${SM_RTL_DIR} -y ${SM_GEN_DIR} -I${SM_GEN_DIR})
set(_sm_vinc ${VERILATOR_ROOT}/include)
find_package(ZLIB REQUIRED)  # FST traces

# Verilator's trace runtime (5.006, and still 5.048) reads its std::vector<bool> of enabled
# trace codes past the end when dumpvars() selects signals: traceInit() calls reserve()
# where resize() is meant, so codes above about twice the last enabled one come out
# enabled at random; the FST writer then crashes on a code it never declared and the VCD
# writer writes values of undeclared identifiers. The trace runtime is compiled from
# copies whose verilated_trace_imp.h has that one line fixed.
set(_sm_trace_src ${_sm_vinc})
file(READ ${_sm_vinc}/verilated_trace_imp.h _sm_imp)
set(_sm_bad "m_sigs_enabledVec.reserve(nextCode());")
string(FIND "${_sm_imp}" "${_sm_bad}" _sm_at)
if(_sm_at EQUAL -1)
  message(STATUS "verilated_trace_imp.h: no reserve() to fix, Verilator's trace runtime is used as it is")
else()
  set(_sm_trace_src ${CMAKE_BINARY_DIR}/verilator_trace_fix)
  string(REPLACE "${_sm_bad}" "m_sigs_enabledVec.resize(nextCode());  // sm: was reserve()" _sm_imp "${_sm_imp}")
  file(WRITE ${_sm_trace_src}/verilated_trace_imp.h.new "${_sm_imp}")
  configure_file(${_sm_trace_src}/verilated_trace_imp.h.new ${_sm_trace_src}/verilated_trace_imp.h COPYONLY)
  # the copies include "verilated_trace_imp.h" from their own folder first
  foreach(f verilated_vcd_c.cpp verilated_fst_c.cpp)
    configure_file(${_sm_vinc}/${f} ${_sm_trace_src}/${f} COPYONLY)
  endforeach()
endif()

# The runtime: sm_verilated (core, threads, coverage), sm_verilated_vcd and
# sm_verilated_fst (trace writers). Verilator's headers are system headers, so the
# project's warnings stay on for every file that includes them.
set(_sm_rt_srcs ${_sm_vinc}/verilated.cpp ${_sm_vinc}/verilated_threads.cpp)
if(SM_COVERAGE)
  list(APPEND _sm_rt_srcs ${_sm_vinc}/verilated_cov.cpp)
endif()
add_library(sm_verilated STATIC ${_sm_rt_srcs})
target_include_directories(sm_verilated SYSTEM PUBLIC ${_sm_vinc} ${_sm_vinc}/vltstd)
target_compile_definitions(sm_verilated PUBLIC VM_SC=0)
target_link_libraries(sm_verilated PUBLIC Threads::Threads)
add_library(sm_verilated_vcd STATIC ${_sm_trace_src}/verilated_vcd_c.cpp)
target_link_libraries(sm_verilated_vcd PUBLIC sm_verilated)
add_library(sm_verilated_fst STATIC ${_sm_trace_src}/verilated_fst_c.cpp)
target_link_libraries(sm_verilated_fst PUBLIC sm_verilated ZLIB::ZLIB)
if(EXISTS ${_sm_vinc}/fstcpp)  # Verilator 5.04x's FST writer compresses with LZ4 as well
  find_path(SM_LZ4_INCLUDE lz4.h REQUIRED)
  find_library(SM_LZ4_LIB lz4 REQUIRED)
  target_include_directories(sm_verilated_fst PRIVATE ${SM_LZ4_INCLUDE})
  target_link_libraries(sm_verilated_fst PUBLIC ${SM_LZ4_LIB})
endif()
if(NOT EXISTS ${_sm_vinc}/gtkwave/fstapi.h)
  # No FST reader in this Verilator (5.04x): sim/sm_wave_names.hpp reads FST files with
  # GTKWave's fstapi from Debian's Verilator package (scripts/deps.sh installs it), copied
  # into the build so that none of that Verilator's other headers are on the include path.
  set(_sm_gtk /usr/share/verilator/include/gtkwave)
  if(NOT EXISTS ${_sm_gtk}/fstapi.c)
    message(FATAL_ERROR "${_sm_gtk}/fstapi.c not found: the FST reader comes from Debian's verilator package (scripts/deps.sh)")
  endif()
  foreach(f fstapi.c fstapi.h fastlz.c fastlz.h lz4.h fst_config.h fst_win_unistd.h wavealloca.h)
    configure_file(${_sm_gtk}/${f} ${CMAKE_BINARY_DIR}/fst_reader/gtkwave/${f} COPYONLY)
  endforeach()
  add_library(sm_fst_reader STATIC ${CMAKE_SOURCE_DIR}/sim/sm_fst_reader.cpp)
  target_include_directories(sm_fst_reader SYSTEM PUBLIC ${CMAKE_BINARY_DIR}/fst_reader)
  target_include_directories(sm_fst_reader PRIVATE ${CMAKE_BINARY_DIR}/fst_reader/gtkwave)
  target_link_libraries(sm_fst_reader PUBLIC ZLIB::ZLIB ${SM_LZ4_LIB} Threads::Threads)
  target_link_libraries(sm_verilated_fst PUBLIC sm_fst_reader)
endif()
foreach(t sm_verilated_vcd sm_verilated_fst)
  target_include_directories(${t} PRIVATE ${_sm_trace_src})
endforeach()

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

# sm_verilate_model(<target> TOP <module> PREFIX <class> [VERILATOR_ARGS ...]
#                   [TRACE | TRACE_FST] [FAST_GROUPS n] [OPT_FAST flags...] [OPT_SLOW flags...])
#   Verilates rtl/<module>.v (submodules from rtl/ and the generated folder) into class
#   <class> and adds its code to <target> (a library or executable; one target may hold
#   several models). The per-cycle code is compiled as FAST_GROUPS files (default 1)
#   with the target's flags plus OPT_FAST; the run-once code (construction, initial
#   blocks, the first settle, trace declarations) as one file at -O0 plus OPT_SLOW:
#   it runs once, and at -O1 GCC spent minutes on a single settle function of the paper
#   configuration's aggregation (29,000 lines). With -DSM_COVERAGE=ON the model has line
#   and toggle coverage.
function(sm_verilate_model target)
  cmake_parse_arguments(V "TRACE;TRACE_FST" "TOP;PREFIX;FAST_GROUPS" "VERILATOR_ARGS;OPT_FAST;OPT_SLOW"
                        ${ARGN})
  if(NOT V_FAST_GROUPS)
    set(V_FAST_GROUPS 1)
  endif()
  set(vdir ${CMAKE_CURRENT_BINARY_DIR}/${V_PREFIX}.vdir)
  set(args --cc --prefix ${V_PREFIX} --Mdir ${vdir} --top-module ${V_TOP} ${SM_VERILATOR_ARGS}
           ${V_VERILATOR_ARGS})
  set(libs sm_verilated)
  set(tr 0)
  set(vcd 0)
  set(fst 0)
  if(V_TRACE)
    list(APPEND args --trace)
    list(APPEND libs sm_verilated_vcd)
    set(tr 1)
    set(vcd 1)
  elseif(V_TRACE_FST)
    list(APPEND args --trace-fst)
    list(APPEND libs sm_verilated_fst)
    set(tr 1)
    set(fst 1)
  endif()
  set(cov 0)
  if(SM_COVERAGE)
    list(APPEND args --coverage-line --coverage-toggle)
    set(cov 1)
  endif()
  set(fast)
  math(EXPR last "${V_FAST_GROUPS} - 1")
  foreach(i RANGE ${last})
    list(APPEND fast ${vdir}/${V_PREFIX}__sm_fast_${i}.cpp)
  endforeach()
  set(slow ${vdir}/${V_PREFIX}__sm_slow_0.cpp)
  add_custom_command(
    OUTPUT ${vdir}/${V_PREFIX}.h ${fast} ${slow}
    COMMAND ${CMAKE_COMMAND} -E env VERILATOR_ROOT=${VERILATOR_ROOT} ${VERILATOR_BIN} ${args} ${SM_RTL_DIR}/${V_TOP}.v
    COMMAND ${CMAKE_COMMAND} -DVDIR=${vdir} -DPREFIX=${V_PREFIX} -DFAST=${V_FAST_GROUPS} -DSLOW=1
            -P ${CMAKE_SOURCE_DIR}/cmake/SmVerilatorGroup.cmake
    DEPENDS ${SM_RTL_FILES} ${VERILATOR_BIN} ${CMAKE_SOURCE_DIR}/cmake/SmVerilatorGroup.cmake
    COMMENT "Verilating ${V_TOP} into ${V_PREFIX}"
    VERBATIM)
  # GCC 12.2 at -O3 vectorizes Verilator's word-by-word copy of a wide temporary (the
  # 3,840-bit write of sm_sw_aggregate's cost window at the paper configuration) with an
  # aligned 16-byte load (movdqa) of a member whose offset in the model is 8 mod 16:
  # SIGSEGV in nba_sequent as soon as the model's layout puts it there (it did when
  # sm_out_support joined sm_top; plain -O3 does the same). Without loop vectorization
  # that copy stays scalar; the straight-line (SLP) vector code, which GCC aligns from the
  # layout, stays.
  set(fast_opts ${V_OPT_FAST})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    list(PREPEND fast_opts -fno-tree-loop-vectorize)
  endif()
  set_source_files_properties(${fast} PROPERTIES COMPILE_OPTIONS "${fast_opts}")
  set_source_files_properties(${slow} PROPERTIES COMPILE_OPTIONS "-O0;${V_OPT_SLOW}")
  target_sources(${target} PRIVATE ${fast} ${slow})
  target_include_directories(${target} SYSTEM PUBLIC ${vdir})  # Verilator's output: no warnings
  # the generated register map (sm_regmap.vh) must exist before Verilator runs
  add_dependencies(${target} sm_regmap_gen_files)
  target_link_libraries(${target} PUBLIC ${libs})
  # VM_*: what the harness and Verilator's headers see of this model's options (the
  # models of one target agree: the wave libraries hold a VCD and an FST model)
  target_compile_definitions(${target} PUBLIC VM_COVERAGE=${cov} VM_TRACE=${tr})
  if(vcd)
    target_compile_definitions(${target} PUBLIC VM_TRACE_VCD=1)
  endif()
  if(fst)
    target_compile_definitions(${target} PUBLIC VM_TRACE_FST=1)
  endif()
endfunction()

# sm_verilated(TARGET <target> TOP <module> [PARAMS NAME=VALUE ...] [TRACE] [THREADS n]
#              [TRACE_DEPTH n] [FAST_GROUPS n] [OPT_FAST flags...] [OPT_SLOW flags...])
#   One model of rtl/<module>.v at one parameter point in <target>, class V<target>.
#   The target gets SM_VTOP / SM_VTOP_H naming the model class and header, and
#   SM_P_<NAME>=<VALUE> for every parameter (PUBLIC: the users of a library see them).
#   With -DSM_COVERAGE=ON the target and its users get SM_COVERAGE=1
#   (tests/common/sm_coverage.hpp).
function(sm_verilated)
  cmake_parse_arguments(V "TRACE" "TARGET;TOP;THREADS;TRACE_DEPTH;FAST_GROUPS"
                        "PARAMS;OPT_FAST;OPT_SLOW;VERILATOR_ARGS" ${ARGN})
  set(args ${V_VERILATOR_ARGS})
  if(V_TRACE_DEPTH)
    list(APPEND args --trace-depth ${V_TRACE_DEPTH})
  endif()
  if(V_THREADS)
    list(APPEND args --threads ${V_THREADS})
  endif()
  set(defs SM_VTOP=V${V_TARGET} SM_VTOP_H="V${V_TARGET}.h")
  sm_param_flags(args defs ${V_PARAMS})
  set(extra)
  if(V_TRACE)
    list(APPEND extra TRACE)
  endif()
  if(V_FAST_GROUPS)
    list(APPEND extra FAST_GROUPS ${V_FAST_GROUPS})
  endif()
  sm_verilate_model(${V_TARGET} TOP ${V_TOP} PREFIX V${V_TARGET} VERILATOR_ARGS ${args}
                    OPT_FAST ${V_OPT_FAST} OPT_SLOW ${V_OPT_SLOW} ${extra})
  target_compile_definitions(${V_TARGET} PUBLIC ${defs})
  if(SM_COVERAGE)
    # tests/common/sm_coverage.hpp writes the data
    target_compile_definitions(${V_TARGET} PUBLIC SM_COVERAGE=1)
  endif()
endfunction()

# sm_rtl_test(NAME <test> TOP <module> SOURCES <tb.cpp ...> [PARAMS ...] [LABELS ...]
#             [ARGS ...] [TRACE] [TIMEOUT s] [VERILATOR_ARGS ...])
# sm_rtl_test(NAME <test> RUN <test of a binary> [ARGS ...] [LABELS ...] [TIMEOUT s])
#   One Verilated block test at one parameter point, registered with ctest: the RTL
#   parameters become SM_P_<NAME> definitions, ARGS the bench's command line (its
#   width, heights, seed, ...: tests/common/sm_block_test.hpp). With RUN, another run
#   of the binary an earlier sm_rtl_test built (same parameters, other ARGS).
function(sm_rtl_test)
  cmake_parse_arguments(T "TRACE" "NAME;TOP;TIMEOUT;RUN" "SOURCES;PARAMS;LABELS;ARGS;VERILATOR_ARGS"
                        ${ARGN})
  if(T_RUN)
    add_test(NAME ${T_NAME} COMMAND ${T_RUN} ${T_ARGS})
  else()
    add_executable(${T_NAME} ${T_SOURCES})
    # the project's warnings on the bench (Verilator's headers and output are system headers)
    set_source_files_properties(${T_SOURCES} PROPERTIES COMPILE_OPTIONS "${SM_WARNINGS}")
    target_include_directories(${T_NAME} PRIVATE ${CMAKE_SOURCE_DIR}/tests/common
                                                 ${CMAKE_SOURCE_DIR}/sim ${SM_GEN_DIR})
    # the bench's own knobs are options (tests/common/sm_bench_options.hpp)
    target_link_libraries(${T_NAME} PRIVATE sm_model sm_bench_options fmt::fmt)
    set(tr)
    if(T_TRACE)
      set(tr TRACE)
    endif()
    sm_verilated(TARGET ${T_NAME} TOP ${T_TOP} PARAMS ${T_PARAMS} VERILATOR_ARGS ${T_VERILATOR_ARGS} ${tr})
    # Block tests run for seconds; their generated C++ (tens of MB at the paper point)
    # compiles several times faster at -O1 than at -O3.
    target_compile_options(${T_NAME} PRIVATE -O1)
    add_test(NAME ${T_NAME} COMMAND ${T_NAME} ${T_ARGS})
  endif()
  if(NOT T_LABELS)
    set(T_LABELS rtl)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT})
endfunction()
