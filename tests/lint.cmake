add_test(NAME lint_rtl COMMAND ${CMAKE_SOURCE_DIR}/tools/lint_rtl.sh ${SM_RTL_DIR} ${SM_GEN_DIR})
set_tests_properties(lint_rtl PROPERTIES LABELS "lint;rtl")
