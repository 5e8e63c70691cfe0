// Place-and-route figures of the ECP5 runs: see sm_pnr_report.hpp.
#include "sm_pnr_report.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace sm::synth {
namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

// nextpnr's names of the ECP5 cells the core can use -> the report's keys.
const std::vector<std::pair<const char*, const char*>>& cell_keys() {
  static const std::vector<std::pair<const char*, const char*>> k = {{"TRELLIS_COMB", "comb"}, {"TRELLIS_FF", "ff"},
                                                                     {"TRELLIS_RAMW", "ramw"}, {"DP16KD", "ebr"},
                                                                     {"MULT18X18D", "mult18"}, {"ALU54B", "alu54"}};
  return k;
}

// The slowest clock of the run, or none.
void add_fmax(const json& fmax, json& out) {
  double least = std::numeric_limits<double>::infinity();
  for (const auto& [clock, f] : fmax.items()) {
    const double a = f.at("achieved").get<double>();
    if (a < least) {
      least = a;
      out["fmax_mhz"] = a;
      out["target_mhz"] = f.at("constraint").get<double>();
      out["clock"] = clock;
    }
  }
}

// The longest of the reported paths: its ends, delays and logic cells.
void add_path(const json& paths, json& out) {
  double worst = -1;
  for (const auto& p : paths) {
    double logic = 0, routing = 0;
    int cells = 0;
    for (const auto& e : p.at("path")) {
      const std::string type = e.at("type").get<std::string>();
      const double d = e.at("delay").get<double>();
      if (type == "routing") {
        routing += d;
      } else {
        logic += d;
        cells += type == "logic";
      }
    }
    if (logic + routing <= worst || p.at("path").empty()) continue;
    worst = logic + routing;
    out["path_logic_ns"] = logic;
    out["path_routing_ns"] = routing;
    out["path_cells"] = cells;
    out["path_from"] = p.at("path").front().at("from").at("cell");
    out["path_to"] = p.at("path").back().at("to").at("cell");
  }
}

std::string mhz(const json& f) {
  return f.contains("fmax_mhz") ? fmt::format("{:.1f}", f["fmax_mhz"].get<double>()) : "-";
}

}  // namespace

json pnr_figures(const json& nextpnr, const std::string& where) {
  try {
    json out = json::object();
    const json& util = nextpnr.at("utilization");
    for (const auto& [cell, key] : cell_keys()) {
      const json none = {{"used", 0}, {"available", 0}};
      const json& u = util.contains(cell) ? util[cell] : none;
      out[key] = u.at("used").get<long long>();
      out[std::string(key) + "_available"] = u.at("available").get<long long>();
    }
    add_fmax(nextpnr.at("fmax"), out);
    add_path(nextpnr.value("critical_paths", json::array()), out);
    return out;
  } catch (const json::exception& e) {
    fail(fmt::format("{}: not a nextpnr report: {}", where, e.what()));
  }
}

json pnr_total(const std::vector<PnrPart>& parts) {
  json total = json::object();
  for (const auto& [cell, key] : cell_keys()) total[key] = 0;
  const PnrPart* slowest = nullptr;
  for (const auto& p : parts) {
    for (const auto& [cell, key] : cell_keys()) {
      total[key] = total[key].get<long long>() + p.figures.value(key, 0LL) * p.instances;
      const std::string avail = std::string(key) + "_available";
      if (p.figures.contains(avail)) total[avail] = p.figures[avail];
    }
    if (p.figures.contains("fmax_mhz") &&
        (!slowest || p.figures["fmax_mhz"].get<double>() < slowest->figures["fmax_mhz"].get<double>()))
      slowest = &p;
  }
  if (slowest) {
    // its clock and critical path: every figure that is not a cell count
    for (const auto& [k, v] : slowest->figures.items())
      if (!total.contains(k)) total[k] = v;
    total["slowest_block"] = slowest->block;
  }
  return total;
}

void print_pnr_report(const json& r, bool md) {
  auto row = [&](const std::string& name, const json& b) {
    const std::string inst = b.contains("instances") ? fmt::format("{}", b["instances"].get<long long>()) : "";
    const std::string path = b.contains("path_cells")
                                 ? fmt::format("{} cells, {:.1f} + {:.1f} ns", b["path_cells"].get<int>(),
                                               b["path_logic_ns"].get<double>(), b["path_routing_ns"].get<double>())
                                 : "-";
    if (md)
      fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", name, inst, b.value("comb", 0LL),
                 b.value("ff", 0LL), b.value("ramw", 0LL), b.value("ebr", 0LL), b.value("mult18", 0LL), mhz(b), path);
    else
      fmt::print("{:<24} {:>4} {:>8} {:>8} {:>6} {:>5} {:>6} {:>8}  {}\n", name, inst, b.value("comb", 0LL),
                 b.value("ff", 0LL), b.value("ramw", 0LL), b.value("ebr", 0LL), b.value("mult18", 0LL), mhz(b), path);
  };
  fmt::print("{} {} ({}, {}, {}; {}; {:.0f} s)\n", md ? "####" : "==", r.value("top", ""), r.value("config", ""),
             r.value("device", ""), r.value("nextpnr", ""), r.value("mode", ""), r.value("seconds", 0.0));
  if (r.contains("missing_blocks") && !r["missing_blocks"].empty())
    fmt::print("{}INCOMPLETE: not placed: {}\n", md ? "\n" : "", r["missing_blocks"].dump());
  if (md)
    fmt::print(
        "\n| block | inst | LUT4 (COMB) | FFs | LUT-RAM (RAMW) | EBR (DP16KD) | MULT18 | Fmax MHz | critical path "
        "(logic + routing) |\n|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  else
    fmt::print("{:<24} {:>4} {:>8} {:>8} {:>6} {:>5} {:>6} {:>8}  {}\n", "block", "inst", "COMB", "FF", "RAMW", "EBR",
               "MULT18", "Fmax", "critical path");
  for (const auto& [name, b] : r["blocks"].items()) row(name, b);
  const json& t = r["total"];
  row(md ? "**total**" : "total", t);
  if (t.contains("fmax_mhz"))
    fmt::print("{}Fmax {:.1f} MHz (target {:.0f}){}; critical path {} -> {}\n", md ? "\n" : "",
               t["fmax_mhz"].get<double>(), t.value("target_mhz", 0.0),
               t.contains("slowest_block") ? fmt::format(", slowest block {}", t["slowest_block"].get<std::string>())
                                           : std::string(),
               t.value("path_from", ""), t.value("path_to", ""));
}

}  // namespace sm::synth
