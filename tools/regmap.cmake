# Register map generator (rtl/regmap.json is the single source of truth). It is built
# first and run at build time; its outputs land in ${SM_GEN_DIR}:
#   sm_regmap.vh   Verilog localparams, included inside rtl/sm_axil_regs.v
#   sm_regmap.hpp  C++ constants + register table for test benches and the harness
#   sm_regvalues.hpp  sm::RegValues: the value registers as members of the model's sm::Regs,
#                  with their reset values (included by model/sm_types.hpp)
#   registers.md   documentation; docs/registers.md must equal it (ctest regmap_doc_current)
# and, from rtl/defs.json (sideband layout, parameter limits, grid geometry):
#   sm_defs.vh        Verilog macros, included by the RTL files that use them
#   sm_defs_check.vh  sm_top's elaboration checks of its parameters
#   sm_defs.hpp       the same constants for C++ (sm::defs), used by the model
# Targets that use the outputs depend on the target sm_regmap_gen_files.
add_executable(sm_regmap_gen ${CMAKE_CURRENT_SOURCE_DIR}/sm_regmap_gen.cpp)
target_link_libraries(sm_regmap_gen PRIVATE nlohmann_json::nlohmann_json fmt::fmt CLI11::CLI11)
target_compile_options(sm_regmap_gen PRIVATE ${SM_WARNINGS})
# toolio/sm_cli.hpp (and sm_json_file.hpp): header-only, no link to sm_toolio
target_include_directories(sm_regmap_gen PRIVATE ${CMAKE_SOURCE_DIR})

set(SM_REGMAP_JSON ${SM_RTL_DIR}/regmap.json)
set(SM_DEFS_JSON ${SM_RTL_DIR}/defs.json)

set(SM_REGMAP_OUTPUTS ${SM_GEN_DIR}/sm_regmap.vh ${SM_GEN_DIR}/sm_regmap.hpp ${SM_GEN_DIR}/sm_regvalues.hpp
                      ${SM_GEN_DIR}/registers.md ${SM_GEN_DIR}/sm_defs.vh
                      ${SM_GEN_DIR}/sm_defs_check.vh ${SM_GEN_DIR}/sm_defs.hpp)
add_custom_command(
  OUTPUT ${SM_REGMAP_OUTPUTS}
  COMMAND sm_regmap_gen ${SM_REGMAP_JSON} ${SM_GEN_DIR} --defs ${SM_DEFS_JSON}
  # the generator leaves unchanged files alone; touch so the outputs are newer than the json
  COMMAND ${CMAKE_COMMAND} -E touch_nocreate ${SM_REGMAP_OUTPUTS}
  DEPENDS sm_regmap_gen ${SM_REGMAP_JSON} ${SM_DEFS_JSON}
  COMMENT "Generating the register map and definitions from rtl/regmap.json, rtl/defs.json"
  VERBATIM)
add_custom_target(sm_regmap_gen_files ALL DEPENDS ${SM_REGMAP_OUTPUTS})

add_test(NAME regmap_doc_current
         COMMAND ${CMAKE_COMMAND} -E compare_files ${CMAKE_SOURCE_DIR}/docs/registers.md
                 ${SM_GEN_DIR}/registers.md)
set_tests_properties(regmap_doc_current PROPERTIES LABELS "unit;lint")
