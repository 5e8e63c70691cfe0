# Streak study (issue 21, docs/evaluation.md "Streak study"): post-filter and inter-scanline
# DP candidates scored on a dataset; part of the tools, never run by the tests.
add_executable(sm_streak_study ${CMAKE_CURRENT_LIST_DIR}/sm_streak_study.cpp)
target_link_libraries(sm_streak_study PRIVATE sm_toolio CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(sm_streak_study PRIVATE ${SM_WARNINGS})
