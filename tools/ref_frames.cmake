# sm_ref_frames: register writes, camera words and the reference model's disparity words
# and object packets of N frames, as one JSON file for external test benches
# (tests/cocotb). It takes the host's register words from sim/sm_regs_io.hpp, whose
# includes need Verilator's headers (nothing of Verilator is linked).
add_executable(sm_ref_frames ${CMAKE_CURRENT_LIST_DIR}/sm_ref_frames.cpp)
target_include_directories(sm_ref_frames PRIVATE ${CMAKE_SOURCE_DIR}/sim ${SM_GEN_DIR})
# (a system include: verilated_types.h trips -Wunused-parameter)
target_include_directories(sm_ref_frames SYSTEM PRIVATE ${VERILATOR_ROOT}/include)
target_link_libraries(sm_ref_frames PRIVATE sm_toolio CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(sm_ref_frames PRIVATE ${SM_WARNINGS})
add_dependencies(sm_ref_frames sm_regmap_gen_files)
