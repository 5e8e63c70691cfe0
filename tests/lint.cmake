add_test(NAME lint_rtl COMMAND ${CMAKE_SOURCE_DIR}/tools/lint_rtl.sh ${SM_RTL_DIR} ${SM_GEN_DIR})
set_tests_properties(lint_rtl PROPERTIES LABELS "lint;rtl")

# C++ style (.clang-format); scripts/deps.sh installs clang-format.
find_program(SM_CLANG_FORMAT clang-format)
if(SM_CLANG_FORMAT)
  add_test(NAME format_cpp COMMAND ${CMAKE_SOURCE_DIR}/tools/check_format.sh ${SM_CLANG_FORMAT})
  set_tests_properties(format_cpp PROPERTIES LABELS "lint")
else()
  message(WARNING "clang-format not found: no format_cpp test (scripts/deps.sh installs it)")
endif()
