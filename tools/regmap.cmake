# Register map generator (rtl/regmap.json is the single source of truth). It is built
# first and run at build time; its outputs land in ${SM_GEN_DIR}:
#   sm_regmap.vh   Verilog localparams, included inside rtl/sm_axil_regs.v
#   sm_regmap.hpp  C++ constants + register table for test benches and the harness
#   registers.md   documentation; docs/registers.md must equal it (ctest regmap_doc_current)
# Targets that use the outputs depend on the target sm_regmap_gen_files.
add_executable(sm_regmap_gen ${CMAKE_CURRENT_SOURCE_DIR}/sm_regmap_gen.cpp)
target_link_libraries(sm_regmap_gen PRIVATE nlohmann_json::nlohmann_json fmt::fmt CLI11::CLI11)
target_compile_options(sm_regmap_gen PRIVATE ${SM_WARNINGS})

set(SM_REGMAP_JSON ${SM_RTL_DIR}/regmap.json)

# verilate() runs Verilator at configure time, so sm_regmap.vh must exist before any
# Verilated target is declared: build the generator with try_compile and run it now as
# well. Editing the json or the generator re-runs the configure step.
set(SM_REGMAP_BOOT ${CMAKE_BINARY_DIR}/regmap_boot/sm_regmap_gen_boot)
try_compile(SM_REGMAP_BOOT_OK ${CMAKE_BINARY_DIR}/regmap_boot/build
            SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/sm_regmap_gen.cpp
            LINK_LIBRARIES nlohmann_json::nlohmann_json fmt::fmt CLI11::CLI11
            CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON
            OUTPUT_VARIABLE SM_REGMAP_BOOT_LOG
            COPY_FILE ${SM_REGMAP_BOOT})
if(NOT SM_REGMAP_BOOT_OK)
  message(FATAL_ERROR "tools/sm_regmap_gen.cpp does not compile:\n${SM_REGMAP_BOOT_LOG}")
endif()
execute_process(COMMAND ${SM_REGMAP_BOOT} ${SM_REGMAP_JSON} ${SM_GEN_DIR}
                RESULT_VARIABLE SM_REGMAP_RC ERROR_VARIABLE SM_REGMAP_ERR)
if(NOT SM_REGMAP_RC EQUAL 0)
  message(FATAL_ERROR "register map generation failed: ${SM_REGMAP_ERR}")
endif()
set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             ${SM_REGMAP_JSON} ${CMAKE_CURRENT_SOURCE_DIR}/sm_regmap_gen.cpp)

set(SM_REGMAP_OUTPUTS ${SM_GEN_DIR}/sm_regmap.vh ${SM_GEN_DIR}/sm_regmap.hpp
                      ${SM_GEN_DIR}/registers.md)
add_custom_command(
  OUTPUT ${SM_REGMAP_OUTPUTS}
  COMMAND sm_regmap_gen ${SM_REGMAP_JSON} ${SM_GEN_DIR}
  # the generator leaves unchanged files alone; touch so the outputs are newer than the json
  COMMAND ${CMAKE_COMMAND} -E touch_nocreate ${SM_REGMAP_OUTPUTS}
  DEPENDS sm_regmap_gen ${SM_REGMAP_JSON}
  COMMENT "Generating the register map from rtl/regmap.json"
  VERBATIM)
add_custom_target(sm_regmap_gen_files ALL DEPENDS ${SM_REGMAP_OUTPUTS})

add_test(NAME regmap_doc_current
         COMMAND ${CMAKE_COMMAND} -E compare_files ${CMAKE_SOURCE_DIR}/docs/registers.md
                 ${SM_GEN_DIR}/registers.md)
set_tests_properties(regmap_doc_current PROPERTIES LABELS "unit;lint")
