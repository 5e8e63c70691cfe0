// Command-line options for the run-time registers (stereo_model, stereo_sim): one option
// per value register of the register map, named after it (OCC_EDGE -> --occ-edge), with
// the map's description as help and the tool's default value, range-checked against the
// map at the configuration in use. A register added to rtl/regmap.json gets its option
// with no edit here.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "sm_types.hpp"

namespace sm::tools {

class RegOptions {
 public:
  // Options for every value register but those in `skip` (map names; SW_TABLE0/1 have
  // none: the tools take --sw-table codes), defaults shown from `defaults`, ranges in the
  // help ("INT in lo..hi") from the map at `hw` (apply() checks them at the run's
  // configuration); `aliases` adds names to a register's option (e.g. {"FILTER_ENABLE", "--filters"}).
  RegOptions(CLI::App& app, const Regs& defaults, const HwConfig& hw, const std::set<std::string>& skip = {},
             const std::map<std::string, std::string>& aliases = {});
  // Writes the options given on the command line into r; a value outside the register's
  // range at hw is a ToolError naming the option.
  void apply(const HwConfig& hw, Regs& r) const;

 private:
  struct Opt {
    std::string reg;
    int64_t value = 0;
    CLI::Option* opt = nullptr;
  };
  std::vector<std::unique_ptr<Opt>> opts_;  // CLI11 keeps pointers to `value`
};

}  // namespace sm::tools
