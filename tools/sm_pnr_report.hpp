// Place-and-route figures of the synthesis flow's ECP5 runs (tools/synth/sm_synth.sh -f
// ecp5: Yosys synth_ecp5, then nextpnr-ecp5; docs/synthesis.md "Place and route"), the
// part of sm_synth_report that reads nextpnr's --report JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sm::synth {

// The figures of one nextpnr run (its --report JSON): the clock's achieved and target
// frequency (the slowest clock when there are several; absent when the design has no
// register-to-register path), the ECP5 cells used, and the critical path: its start and end
// cell, logic and routing delay, the logic cells on it. `where` names the file in errors.
nlohmann::json pnr_figures(const nlohmann::json& nextpnr, const std::string& where);

// A part of a sum of blocks: its figures and how many times the parent holds it.
struct PnrPart {
  std::string block;
  nlohmann::json figures;
  long long instances = 1;
};

// The sum of separately placed blocks: cells times instances added up; the frequency and
// critical path of the slowest block (each block's clock is its own, so the sum's is the
// least of them), named in "slowest_block".
nlohmann::json pnr_total(const std::vector<PnrPart>& parts);

// The table `sm_synth_report show` prints for a report of family ecp5.
void print_pnr_report(const nlohmann::json& report, bool markdown);

}  // namespace sm::synth
