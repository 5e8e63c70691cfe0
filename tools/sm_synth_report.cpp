// Resource and logic-depth report of a Yosys synth_xilinx run (docs/synthesis.md).
//
//   sm_synth_report report   --stat S.json --netlist N.json --top MOD ... -o R.json
//       Yosys `stat -json` (hierarchy kept) -> resources per block and in total;
//       the flattened mapped netlist (`write_json`) -> LUT levels between registers.
//   sm_synth_report combine  -o R.json PART.json[@N]... sum of separately mapped blocks
//   sm_synth_report children --stat ELAB.json --top MOD  direct submodules (blocks mode)
//   sm_synth_report show     R.json... [--markdown] [--require-bram]
//   sm_synth_report pnr      --nextpnr P.json --top MOD ... -o R.json
//       nextpnr-ecp5's --report JSON -> a report of family ecp5 (sm_pnr_report.hpp);
//       combine sums such reports too (Fmax: the slowest block's), show prints them
//
// Resource classes (Xilinx primitives as Yosys 0.23 emits them for xc7 and xc5v):
//   luts      every slice LUT: logic LUTs + LUTs used as RAM + SRLs (the figure a vendor
//             report calls "slice LUTs"); luts_logic / lut_by_size: LUT1..LUT6 cells
//   ffs       FD* flip-flops;  bram36: block RAM in 36 Kb equivalents (RAMB18 = 0.5)
//   lutram    LUTs used as distributed RAM (RAM64M = 4, RAM64X1D = 2, ...)
//   srl       SRL16E / SRLC32E shift registers (one LUT each);  dsp: DSP48 slices
// Logic depth: LUT cells on the longest path between path boundaries in the flattened
// netlist. Boundaries: flip-flops, block RAM, SRLs, DSPs, module ports (every stage's
// outputs are registers, so port-to-register paths are halves of register-to-register
// paths across blocks). LUT-RAM read ports count as one LUT (address -> data is
// combinational; data/write-enable inputs end paths). MUXF7/MUXF8 count 0 (they extend
// a LUT inside the slice), CARRY4 counts 0 (reported separately as carry_on_path),
// INV counts 0 (absorbed into the neighbouring LUT by place and route).
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "sm_pnr_report.hpp"
#include "toolio/sm_cli.hpp"
#include "toolio/sm_json_file.hpp"

using json = nlohmann::json;

namespace {

// One error line "sm_synth_report: error: <msg>" and exit 1 (run_guarded in main).
[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

// One JSON value per file, no key twice (toolio/sm_json_file.hpp).
json load(const std::string& path) {
  try {
    return sm::tools::read_json_file(path);
  } catch (const sm::tools::JsonFileError& e) {
    fail(e.what());
  }
}

// A report read back (show, combine): the keys this tool reads have the types it writes,
// else "<file>: '<key>' must be <type>, not <value>". Absent keys read as 0 / "".
void check_report(const std::string& path, const json& r) {
  auto need = [&](const json& obj, const std::string& where, const char* key, bool (json::*is)() const noexcept,
                  const char* type, bool required) {
    const auto it = obj.find(key);
    if (it == obj.end()) {
      if (required) fail(fmt::format("{}: not a report (no '{}{}')", path, where, key));
      return;
    }
    if (!((*it).*is)()) fail(fmt::format("{}: '{}{}' must be {}, not {}", path, where, key, type, it->dump()));
  };
  if (!r.is_object()) fail(fmt::format("{}: not a report (not a JSON object)", path));
  need(r, "", "total", &json::is_object, "an object", true);
  need(r, "", "blocks", &json::is_object, "an object", true);
  for (const char* k : {"tool", "yosys", "top", "family", "config", "mode", "command"})
    need(r, "", k, &json::is_string, "a string", false);
  need(r, "", "seconds", &json::is_number, "a number", false);
  need(r, "", "comb_loops", &json::is_number_integer, "an integer", false);
  for (const char* k : {"critical_path", "missing_blocks", "parts"}) need(r, "", k, &json::is_array, "an array", false);
  // the resource figures of the total and of every block
  auto figures = [&](const json& b, const std::string& where) {
    for (const char* k : {"luts", "luts_logic", "ffs", "latches", "lutram", "srl", "dsp", "muxf", "carry", "unmapped",
                          "instances", "lut_levels", "lut_levels_reg2reg", "carry_on_path"})
      need(b, where, k, &json::is_number_integer, "an integer", false);
    need(b, where, "bram36", &json::is_number, "a number", false);
    for (const char* k : {"lut_by_size", "bram_cells", "other"}) {
      need(b, where, k, &json::is_object, "an object", false);
      if (b.contains(k))
        for (const auto& [n, v] : b[k].items())
          if (!v.is_number_integer())
            fail(fmt::format("{}: '{}{}.{}' must be an integer, not {}", path, where, k, n, v.dump()));
    }
  };
  figures(r["total"], "total.");
  for (const auto& [name, b] : r["blocks"].items()) {
    if (!b.is_object()) fail(fmt::format("{}: 'blocks.{}' must be an object, not {}", path, name, b.dump()));
    figures(b, "blocks." + name + ".");
  }
}

// f() on a Yosys JSON file: a value of an unexpected type is one error line naming the file.
template <class F>
auto yosys_json(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const json::exception& e) {
    fail(fmt::format("{}: unexpected Yosys JSON: {}", path, sm::tools::detail::json_error_text(e.what())));
  }
}

// A report for show / combine: load + check_report.
json load_report(const std::string& path) {
  json r = load(path);
  check_report(path, r);
  return r;
}

std::string load_text(const std::string& path) {
  try {
    return sm::tools::read_text_file(path);
  } catch (const sm::tools::JsonFileError& e) {
    fail(e.what());
  }
}

// Yosys 0.23's `stat -json` prints lines of its text "design hierarchy" listing into the
// JSON when a module is instantiated more than once; such lines never start like JSON.
json load_stat(const std::string& path) {
  std::istringstream f(load_text(path));
  std::string text, line;
  while (std::getline(f, line)) {
    auto p = line.find_first_not_of(" \t\r");
    if (p != std::string::npos && std::string("\"{}[]").find(line[p]) == std::string::npos) continue;
    text += line;
    text += '\n';
  }
  try {
    return sm::tools::parse_json_strict(text, path);
  } catch (const sm::tools::JsonFileError& e) {
    fail(e.what());
  }
}

// Written under a temporary name and renamed: no partial report under `path`.
void save(const std::string& path, const json& j) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << j.dump(2) << "\n";
    if (!f.flush()) {
      std::remove(tmp.c_str());
      fail(fmt::format("{}: cannot write", path));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    fail(fmt::format("{}: cannot write", path));
  }
}

// Yosys names: "\sm_census" (public), "$paramod$<hash>\sm_linebuf" (derived, long
// parameter lists) and "$paramod\sm_popcount\N=32'..." (derived, short ones).
std::string norm(const std::string& n) { return !n.empty() && n[0] == '\\' ? n.substr(1) : n; }
std::string base_name(const std::string& n) {
  if (n.rfind("$paramod\\", 0) == 0) {
    const auto e = n.find('\\', 9);
    return n.substr(9, e == std::string::npos ? std::string::npos : e - 9);
  }
  auto p = n.rfind('\\');
  return p == std::string::npos ? n : n.substr(p + 1);
}
// A module's cell counts by type (an empty object when it has none).
const json& by_type(const json& m) {
  static const json empty = json::object();
  auto it = m.find("num_cells_by_type");
  return it == m.end() ? empty : *it;
}
bool starts(const std::string& s, const char* p) { return s.rfind(p, 0) == 0; }
bool is_submodule_type(const std::string& t) {
  std::string n = norm(t);
  return starts(n, "$paramod") || starts(n, "sm_");
}
std::string strip_clk_suffix(const std::string& t) {  // RAM64X1D_1 (falling edge) etc.
  return t.size() > 2 && t.compare(t.size() - 2, 2, "_1") == 0 ? t.substr(0, t.size() - 2) : t;
}

// LUTs occupied by one distributed-RAM primitive.
int lutram_luts(const std::string& type) {
  static const std::map<std::string, int> k = {
      {"RAM16X1S", 1}, {"RAM32X1S", 1}, {"RAM64X1S", 1}, {"RAM128X1S", 2}, {"RAM256X1S", 4}, {"RAM512X1S", 8},
      {"RAM16X1D", 2}, {"RAM32X1D", 2}, {"RAM64X1D", 2}, {"RAM128X1D", 4}, {"RAM256X1D", 8}, {"RAM32M", 4},
      {"RAM64M", 4},   {"RAM32M16", 8}, {"RAM64M8", 8},  {"RAM16X2S", 2},  {"RAM16X4S", 4},  {"RAM16X8S", 8},
      {"RAM32X2S", 2}, {"RAM32X4S", 4}, {"RAM32X8S", 8}, {"RAM64X2S", 2}};
  auto it = k.find(strip_clk_suffix(type));
  return it == k.end() ? 1 : it->second;
}
bool is_lutram(const std::string& t) { return starts(t, "RAM") && !starts(t, "RAMB"); }
double bram36_of(const std::string& t) {
  if (starts(t, "RAMB36") || starts(t, "FIFO36")) return 1.0;
  if (starts(t, "RAMB18") || starts(t, "FIFO18") || starts(t, "RAMB16")) return 0.5;
  if (starts(t, "RAMB8")) return 0.25;
  if (starts(t, "RAMB4")) return 4.0 / 36.0;
  return 0.0;
}
int lut_size(const std::string& t) {  // 1..6 for LUTn / LUT6_2, 0 otherwise
  if (t.size() >= 4 && starts(t, "LUT") && t[3] >= '1' && t[3] <= '6' && (t.size() == 4 || t == "LUT6_2"))
    return t[3] - '0';
  return 0;
}

struct Res {
  std::map<std::string, int64_t> lut_by_size, bram_cells, other;
  int64_t luts_logic = 0, ffs = 0, latches = 0, lutram = 0, srl = 0, dsp = 0, muxf = 0, carry = 0, unmapped = 0;
  double bram36 = 0;

  void add_cell(const std::string& t, int64_t n) {
    if (int s = lut_size(t)) {
      luts_logic += n;
      lut_by_size[fmt::format("LUT{}", s)] += n;
    } else if (starts(t, "FD")) {
      ffs += n;
    } else if (starts(t, "LD")) {
      latches += n;
    } else if (double b = bram36_of(t); b > 0) {
      bram36 += b * static_cast<double>(n);
      bram_cells[t] += n;
    } else if (is_lutram(t)) {
      lutram += n * lutram_luts(t);
    } else if (starts(t, "SRL")) {
      srl += n;
    } else if (starts(t, "DSP48") || starts(t, "MULT18X18")) {
      dsp += n;
    } else if (starts(t, "MUXF")) {
      muxf += n;
    } else if (t == "CARRY4" || t == "CARRY8" || t == "MUXCY" || t == "XORCY") {
      carry += n;
    } else {
      if (starts(t, "$")) unmapped += n;  // a Yosys internal cell left unmapped
      other[t] += n;
    }
  }
  void add(const Res& r, int64_t mult = 1) {
    for (auto& [k, v] : r.lut_by_size) lut_by_size[k] += v * mult;
    for (auto& [k, v] : r.bram_cells) bram_cells[k] += v * mult;
    for (auto& [k, v] : r.other) other[k] += v * mult;
    luts_logic += r.luts_logic * mult;
    ffs += r.ffs * mult;
    latches += r.latches * mult;
    lutram += r.lutram * mult;
    srl += r.srl * mult;
    dsp += r.dsp * mult;
    muxf += r.muxf * mult;
    carry += r.carry * mult;
    unmapped += r.unmapped * mult;
    bram36 += r.bram36 * static_cast<double>(mult);
  }
  int64_t luts() const { return luts_logic + lutram + srl; }
  json to_json() const {
    return json{{"luts", luts()},
                {"luts_logic", luts_logic},
                {"lut_by_size", lut_by_size},
                {"ffs", ffs},
                {"latches", latches},
                {"bram36", bram36},
                {"bram_cells", bram_cells},
                {"lutram", lutram},
                {"srl", srl},
                {"dsp", dsp},
                {"muxf", muxf},
                {"carry", carry},
                {"unmapped", unmapped},
                {"other", other}};
  }
  static Res from_json(const json& j) {
    Res r;
    r.lut_by_size = j.value("lut_by_size", std::map<std::string, int64_t>{});
    r.bram_cells = j.value("bram_cells", std::map<std::string, int64_t>{});
    r.other = j.value("other", std::map<std::string, int64_t>{});
    r.luts_logic = j.value("luts_logic", int64_t{0});
    r.ffs = j.value("ffs", int64_t{0});
    r.latches = j.value("latches", int64_t{0});
    r.lutram = j.value("lutram", int64_t{0});
    r.srl = j.value("srl", int64_t{0});
    r.dsp = j.value("dsp", int64_t{0});
    r.muxf = j.value("muxf", int64_t{0});
    r.carry = j.value("carry", int64_t{0});
    r.unmapped = j.value("unmapped", int64_t{0});
    r.bram36 = j.value("bram36", 0.0);
    return r;
  }
};

// ---------------------------------------------------------------- stat -json -> blocks
struct StatResult {
  std::map<std::string, Res> blocks;  // base module name -> own cells x instances
  std::map<std::string, int64_t> instances;
  Res total;
};

StatResult parse_stat(const json& stat, const std::string& top, int64_t top_instances) {
  if (!stat.contains("modules")) fail("stat JSON has no \"modules\" (was it `stat -json`?)");
  std::map<std::string, const json*> mods;  // normalized name -> module
  for (auto& [name, m] : stat["modules"].items()) mods[norm(name)] = &m;
  if (!mods.count(norm(top))) fail(fmt::format("module '{}' not in the stat JSON", top));
  // Multiplicity of every module below top (the hierarchy is a DAG).
  std::map<std::string, int64_t> mult;
  std::function<void(const std::string&, int64_t)> walk = [&](const std::string& m, int64_t k) {
    mult[m] += k;
    for (auto& [t, n] : by_type(*mods[m]).items())
      if (mods.count(norm(t))) walk(norm(t), k * n.get<int64_t>());
  };
  walk(norm(top), top_instances);
  StatResult r;
  for (auto& [m, k] : mult) {
    Res own;
    for (auto& [t, n] : by_type(*mods[m]).items())
      if (!mods.count(norm(t)) && !is_submodule_type(t)) own.add_cell(t, n.get<int64_t>());
    std::string b = base_name(m);
    r.blocks[b].add(own, k);
    r.instances[b] += k;
    r.total.add(own, k);
  }
  return r;
}

// ---------------------------------------------------- flattened netlist -> logic depth
struct Depth {
  int levels = 0, levels_reg2reg = 0, carry_on_path = 0, loops = 0;
  std::vector<std::string> path;
  std::map<std::string, int> per_block;  // by the source file of the path's end point
};

std::string src_of(const json& cell) {
  // "a|b|...": after flatten the instance's location comes first and the innermost
  // module's own line last; Yosys techmap library files are skipped.
  std::string all = cell.value("attributes", json::object()).value("src", std::string());
  std::string s;
  for (size_t b = 0; b <= all.size();) {
    size_t e = std::min(all.find('|', b), all.size());
    std::string seg = all.substr(b, e - b);
    if (s.empty() || seg.find("/share/yosys/") == std::string::npos) s = seg;
    b = e + 1;
  }
  auto slash = s.rfind('/');
  return slash == std::string::npos ? s : s.substr(slash + 1);
}
std::string module_of_src(const std::string& src) {
  auto dot = src.find(".v:");
  return dot == std::string::npos ? std::string() : src.substr(0, dot);
}

Depth logic_depth(const json& net, const std::string& top) {
  const json* mod = nullptr;
  for (auto& [name, m] : net["modules"].items()) {
    auto a = m.value("attributes", json::object());
    bool is_top = a.contains("top") && a["top"] != "00000000000000000000000000000000" && a["top"] != 0;
    if (is_top || (!mod && norm(name) == norm(top))) mod = &m;
    if (is_top) break;
  }
  if (!mod) fail(fmt::format("netlist: top module '{}' not found", top));

  enum Kind { SEQ, COMB, SRC };
  struct Cell {
    const json* j;
    std::string type;
    Kind kind;
    int weight;
    std::vector<int64_t> thru;  // input bits that propagate to the outputs
    int level = -1;             // memo (ports-as-sources run)
    int pred = -1;              // cell giving the maximum (-1: a boundary)
    int state = 0;              // 0 new, 1 on stack, 2 done
  };
  std::vector<Cell> cells;
  std::unordered_map<int64_t, int> driver;                      // bit -> comb cell index
  std::unordered_map<int64_t, int> seq_out;                     // bit -> 1: boundary output (register)
  std::vector<std::pair<int, std::vector<int64_t>>> endpoints;  // (cell or -1, bits)
  auto bits_of = [](const json& conn) {
    std::vector<int64_t> b;
    for (auto& x : conn)
      if (x.is_number()) b.push_back(x.get<int64_t>());
    return b;
  };

  for (auto& [cname, c] : (*mod)["cells"].items()) {
    Cell cl{&c, c.value("type", std::string()), SEQ, 0, {}};
    std::string t = cl.type;
    bool lram = is_lutram(t);
    if (lut_size(t))
      cl.kind = COMB, cl.weight = 1;
    else if (lram)
      cl.kind = COMB, cl.weight = 1;
    else if (starts(t, "MUXF") || t == "CARRY4" || t == "CARRY8" || t == "MUXCY" || t == "XORCY" || t == "INV" ||
             t == "BUF")
      cl.kind = COMB, cl.weight = 0;
    else if (t == "GND" || t == "VCC")
      cl.kind = SRC;
    else if (starts(t, "$_") && !starts(t, "$_DFF") && !starts(t, "$_SDFF") && !starts(t, "$_DLATCH"))
      cl.kind = COMB, cl.weight = 1;  // unmapped gate: count it like a LUT
    int idx = static_cast<int>(cells.size());
    auto dirs = c.value("port_directions", json::object());
    std::vector<int64_t> ends;
    for (auto& [p, conn] : c["connections"].items()) {
      std::string d = dirs.value(p, std::string("input"));
      auto b = bits_of(conn);
      if (d == "output") {
        for (auto x : b) {
          if (cl.kind == COMB)
            driver[x] = idx;
          else
            seq_out[x] = 1;
        }
      } else if (cl.kind == COMB) {
        // LUT-RAM: only the read addresses are combinational to the data outputs.
        bool thru = !lram || starts(p, "A") || starts(p, "DPRA");
        if (thru)
          cl.thru.insert(cl.thru.end(), b.begin(), b.end());
        else
          ends.insert(ends.end(), b.begin(), b.end());
      } else if (cl.kind == SEQ) {
        ends.insert(ends.end(), b.begin(), b.end());
      }
    }
    if (!ends.empty()) endpoints.emplace_back(idx, std::move(ends));
    cells.push_back(std::move(cl));
  }
  std::set<int64_t> in_ports;
  for (auto& [pname, p] : (*mod)["ports"].items()) {
    auto b = bits_of(p["bits"]);
    if (p.value("direction", std::string()) == "input")
      in_ports.insert(b.begin(), b.end());
    else
      endpoints.emplace_back(-1, b);
  }

  Depth d;
  // Longest path, memoised, iterative DFS. from_ports: module inputs count as sources
  // (otherwise paths that start at a port are not counted).
  auto run = [&](bool from_ports) {
    const int NONE = -1000000;
    for (auto& c : cells) c.level = NONE, c.pred = -1, c.state = 0;
    auto bit_level = [&](int64_t b, int& pred) -> int {
      pred = -1;
      if (auto it = driver.find(b); it != driver.end()) {
        pred = it->second;
        return cells[it->second].level;
      }
      if (seq_out.count(b)) return 0;
      if (in_ports.count(b)) return from_ports ? 0 : NONE;
      return NONE;  // constant or undriven
    };
    auto eval = [&](int root) {
      std::vector<std::pair<int, size_t>> st{{root, 0}};
      cells[root].state = 1;
      while (!st.empty()) {
        auto& [ci, k] = st.back();
        Cell& c = cells[ci];
        if (k < c.thru.size()) {
          auto it = driver.find(c.thru[k++]);
          if (it != driver.end()) {
            Cell& n = cells[it->second];
            if (n.state == 0) {
              n.state = 1;
              st.emplace_back(it->second, 0);
            } else if (n.state == 1) {
              d.loops++;  // combinational loop: that edge is ignored
            }
          }
          continue;
        }
        int best = NONE, bp = -1;
        for (auto b : c.thru) {
          int p;
          auto itd = driver.find(b);
          if (itd != driver.end() && cells[itd->second].state != 2) continue;  // loop edge
          int l = bit_level(b, p);
          if (l > best) best = l, bp = p;
        }
        if (c.thru.empty()) best = 0;  // a LUT with constant inputs only
        c.level = best == NONE ? NONE : best + c.weight;
        c.pred = bp;
        c.state = 2;
        st.pop_back();
      }
    };
    for (size_t i = 0; i < cells.size(); ++i)
      if (cells[i].kind == COMB && cells[i].state == 0) eval(static_cast<int>(i));
    int best = 0, best_pred = -1, best_end = -2;
    std::map<std::string, int> per_block;
    for (auto& [ci, bits] : endpoints) {
      for (auto b : bits) {
        int p;
        int l = bit_level(b, p);
        if (l < 0) continue;
        if (ci >= 0) {
          std::string m = module_of_src(src_of(*cells[ci].j));
          if (!m.empty()) per_block[m] = std::max(per_block[m], l);
        }
        if (l > best) best = l, best_pred = p, best_end = ci;
      }
    }
    return std::tuple(best, best_pred, best_end, per_block);
  };

  auto [lv_r, pr_r, en_r, pb_r] = run(false);
  d.levels_reg2reg = lv_r;
  auto [lv, pred, end, per_block] = run(true);
  d.levels = lv;
  d.per_block = per_block;
  // Critical path, start to end: cell type and source location.
  std::vector<std::string> rev;
  rev.push_back(end >= 0 ? fmt::format("end {} {}", cells[end].type, src_of(*cells[end].j))
                         : std::string("end output port"));
  for (int c = pred; c >= 0; c = cells[c].pred) {
    if (cells[c].type == "CARRY4" || cells[c].type == "CARRY8") d.carry_on_path++;
    if (cells[c].weight > 0 || cells[c].type != "INV")
      rev.push_back(fmt::format("{} {}", cells[c].type, src_of(*cells[c].j)));
    if (rev.size() > 400) break;
  }
  d.path.assign(rev.rbegin(), rev.rend());
  return d;
}

json params_json(const std::vector<std::string>& ps) {
  json j = json::object();
  for (auto& p : ps) {
    auto eq = p.find('=');
    if (eq == std::string::npos) fail(fmt::format("bad parameter '{}' (want NAME=VALUE)", p));
    std::string v = p.substr(eq + 1);
    try {
      j[p.substr(0, eq)] = std::stoll(v);
    } catch (...) {
      j[p.substr(0, eq)] = v;
    }
  }
  return j;
}

// The fields every report starts with, a single run's and a sum of blocks' alike.
json report_head(const std::string& yosys, const std::string& top, const std::string& family, const std::string& config,
                 const std::vector<std::string>& params, const char* mode, double seconds) {
  return {
      {"tool", "sm_synth_report"},     {"yosys", yosys}, {"top", top},        {"family", family}, {"config", config},
      {"params", params_json(params)}, {"mode", mode},   {"seconds", seconds}};
}

std::string num(double v) {
  return v == static_cast<int64_t>(v) ? fmt::format("{}", static_cast<int64_t>(v)) : fmt::format("{:.1f}", v);
}

void print_report(const json& r, bool md) {
  auto row = [&](const std::string& name, const json& b, int64_t inst) {
    std::string lv = b.contains("lut_levels") ? fmt::format("{}", b["lut_levels"].get<int>()) : std::string("-");
    std::string in = inst > 0 ? fmt::format("{}", inst) : std::string("");
    if (md)
      fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", name, in, b.value("luts", 0), b.value("ffs", 0),
                 num(b.value("bram36", 0.0)), b.value("lutram", 0), b.value("srl", 0), b.value("dsp", 0), lv);
    else
      fmt::print("{:<24} {:>4} {:>9} {:>9} {:>7} {:>7} {:>6} {:>4} {:>6}\n", name, in, b.value("luts", 0),
                 b.value("ffs", 0), num(b.value("bram36", 0.0)), b.value("lutram", 0), b.value("srl", 0),
                 b.value("dsp", 0), lv);
  };
  fmt::print("{} {} ({}, {}; {}; {:.0f} s)\n", md ? "####" : "==", r.value("top", ""), r.value("config", ""),
             r.value("family", ""), r.value("mode", ""), r.value("seconds", 0.0));
  if (r.contains("missing_blocks") && !r["missing_blocks"].empty())
    fmt::print("{}INCOMPLETE: not synthesized: {}\n", md ? "\n" : "", r["missing_blocks"].dump());
  if (md)
    fmt::print(
        "\n| block | inst | LUTs | FFs | BRAM36 | LUT-RAM | SRL | DSP | LUT levels |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  else
    fmt::print("{:<24} {:>4} {:>9} {:>9} {:>7} {:>7} {:>6} {:>4} {:>6}\n", "block", "inst", "LUTs", "FFs", "BRAM36",
               "LUTRAM", "SRL", "DSP", "levels");
  for (auto& [name, b] : r["blocks"].items()) row(name, b, b.value("instances", int64_t{0}));
  row(md ? "**total**" : "total", r["total"], 0);
  const json& t = r["total"];
  fmt::print(
      "{}LUTs by size {}; MUXF {}; CARRY {}; reg-to-reg levels {}; carry cells on "
      "the longest path {}{}\n",
      md ? "\n" : "", t.value("lut_by_size", json::object()).dump(), t.value("muxf", 0), t.value("carry", 0),
      t.value("lut_levels_reg2reg", 0), t.value("carry_on_path", 0),
      t.value("unmapped", 0) ? fmt::format("; UNMAPPED cells {}", t["unmapped"].get<int>()) : std::string());
}

// "report.json@N": a part used N times (its report was made for one instance).
std::pair<std::string, int64_t> part_arg(const std::string& arg) {
  const size_t at = arg.rfind('@'), slash = arg.rfind('/');
  if (at == std::string::npos || (slash != std::string::npos && at < slash)) return {arg, 1};
  const std::string n = arg.substr(at + 1);
  if (n.empty() || n.size() > 6 || n.find_first_not_of("0123456789") != std::string::npos || std::stoll(n) < 1)
    fail(fmt::format("{}: bad instance count '{}' (want 1..999999)", arg, n));
  return {arg.substr(0, at), std::stoll(n)};
}

// combine for family ecp5: every part is one placed block; parts of one module (at
// different parameters) make one row, their cells added up, their slowest clock.
void combine_pnr(const std::vector<std::string>& inputs, const std::string& top, const std::string& config,
                 const std::vector<std::string>& params, const std::vector<std::string>& missing,
                 const std::string& out, bool quiet) {
  std::vector<sm::synth::PnrPart> parts;
  std::map<std::string, std::vector<sm::synth::PnrPart>> by_block;
  json runs = json::array();
  double secs = 0;
  std::string device, version;
  for (const auto& arg : inputs) {
    const auto [in, k] = part_arg(arg);
    const json p = load_report(in);
    if (p.value("family", "") != "ecp5") fail(fmt::format("{}: not a report of family ecp5", in));
    const std::string block = p.value("top", "");
    parts.push_back({block, p["total"], p["blocks"].value(block, json::object()).value("instances", int64_t{1}) * k});
    by_block[block].push_back(parts.back());
    secs += p.value("seconds", 0.0);
    device = p.value("device", "");
    version = p.value("nextpnr", "");
    runs.push_back({{"top", block}, {"seconds", p.value("seconds", 0.0)}, {"command", p.value("command", "")}});
  }
  json r = report_head("", top, "ecp5", config, params, "sum of blocks", secs);
  r["device"] = device;
  r["nextpnr"] = version;
  r["parts"] = runs;
  r["missing_blocks"] = missing;
  r["blocks"] = json::object();
  for (const auto& [block, group] : by_block) {
    json row = sm::synth::pnr_total(group);
    row.erase("slowest_block");
    int64_t n = 0;
    for (const auto& g : group) n += g.instances;
    row["instances"] = n;
    r["blocks"][block] = row;
  }
  r["total"] = sm::synth::pnr_total(parts);
  save(out, r);
  if (!quiet) sm::synth::print_pnr_report(r, false);
}

int run(int argc, char** argv) {
  CLI::App app{"Resource and logic-depth report of the Yosys synthesis flow"};
  app.require_subcommand(1);

  std::string stat_path, net_path, top, family, config, out, command;
  std::vector<std::string> params, inputs;
  double seconds = 0;
  int64_t instances = 1;
  bool quiet = false, md = false, need_bram = false;

  auto* rep = app.add_subcommand("report", "make a report from one Yosys run");
  rep->add_option("--stat", stat_path, "Yosys `stat -json` output")->required();
  rep->add_option("--netlist", net_path, "flattened mapped netlist (write_json); optional");
  rep->add_option("--top", top, "synthesized module as named in the design")->required();
  rep->add_option("--family", family, "synth_xilinx family")->required();
  rep->add_option("--config", config, "configuration name")->required();
  rep->add_option("--param", params, "NAME=VALUE applied to the module");
  // the options of a report made from one run (report, pnr)
  const auto run_options = [&](CLI::App* c, const char* seconds_of) {
    c->add_option("--seconds", seconds, seconds_of)->check(sm::tools::finite_in(0, 1e9));
    c->add_option("--command", command, "how the run was made");
    c->add_option("--instances", instances, "instances of this module in its parent")
        ->check(sm::tools::int_in(1, 1000000));
    c->add_option("-o", out, "output JSON")->required();
    c->add_flag("--quiet", quiet, "no table on stdout");
  };
  run_options(rep, "Yosys run time");

  auto* comb = app.add_subcommand("combine", "sum reports of separately mapped blocks");
  comb->add_option("--top", top, "top module")->required();
  comb->add_option("--family", family, "synth_xilinx family")->required();
  comb->add_option("--config", config, "configuration name")->required();
  comb->add_option("--param", params, "NAME=VALUE of the configuration");
  comb->add_option("-o", out, "output JSON")->required();
  comb->add_option("parts", inputs, "part reports; report.json@N counts a part N times")->required();
  comb->add_flag("--quiet", quiet, "no table on stdout");
  std::vector<std::string> missing;
  comb->add_option("--missing", missing, "blocks that could not be synthesized");

  auto* kids = app.add_subcommand("children", "direct submodules of a module (elaborated)");
  kids->add_option("--stat", stat_path, "Yosys `stat -json` of the elaborated design")->required();
  kids->add_option("--top", top, "parent module")->required();

  std::string pnr_path, device, pnr_version;
  auto* pnr = app.add_subcommand("pnr", "make a report of family ecp5 from one nextpnr-ecp5 run");
  pnr->add_option("--nextpnr", pnr_path, "nextpnr's --report JSON")->required();
  pnr->add_option("--top", top, "placed module")->required();
  pnr->add_option("--config", config, "configuration name")->required();
  pnr->add_option("--param", params, "NAME=VALUE applied to the module");
  pnr->add_option("--device", device, "device, speed grade and package")->required();
  pnr->add_option("--tool-version", pnr_version, "nextpnr's --version line");
  run_options(pnr, "Yosys and nextpnr run time");

  auto* show = app.add_subcommand("show", "print reports as a table");
  show->add_option("reports", inputs, "report JSON files")->required()->check(CLI::ExistingFile);
  show->add_flag("--markdown", md, "markdown table (docs/synthesis.md)");
  show->add_flag("--require-bram", need_bram, "exit 1 when a report holds no block RAM");

  if (const auto rc = sm::tools::parse_cli(app, argc, argv)) return *rc;

  if (*pnr) {
    json r = report_head("", top, "ecp5", config, params, "single run", seconds);
    r["device"] = device;
    r["nextpnr"] = pnr_version;
    r["command"] = command;
    r["total"] = sm::synth::pnr_figures(load(pnr_path), pnr_path);
    r["blocks"] = {{top, r["total"]}};
    r["blocks"][top]["instances"] = instances;
    save(out, r);
    if (!quiet) sm::synth::print_pnr_report(r, false);
  } else if (*rep) {
    json stat = load_stat(stat_path);
    StatResult s = yosys_json(stat_path, [&] { return parse_stat(stat, top, instances); });
    json r =
        report_head(stat.value("creator", ""), base_name(norm(top)), family, config, params, "single run", seconds);
    r["command"] = command;
    r["total"] = s.total.to_json();
    r["blocks"] = json::object();
    for (auto& [b, res] : s.blocks) {
      r["blocks"][b] = res.to_json();
      r["blocks"][b]["instances"] = s.instances[b];
    }
    if (!net_path.empty()) {
      const json net = load(net_path);
      const Depth d = yosys_json(net_path, [&] { return logic_depth(net, top); });
      r["total"]["lut_levels"] = d.levels;
      r["total"]["lut_levels_reg2reg"] = d.levels_reg2reg;
      r["total"]["carry_on_path"] = d.carry_on_path;
      r["comb_loops"] = d.loops;
      r["critical_path"] = d.path;
      for (auto& [m, l] : d.per_block)
        if (r["blocks"].contains(m)) r["blocks"][m]["lut_levels"] = l;
    }
    save(out, r);
    if (!quiet) print_report(r, false);
  } else if (*comb && family == "ecp5") {
    combine_pnr(inputs, top, config, params, missing, out, quiet);
  } else if (*comb) {
    Res total;
    std::map<std::string, Res> blocks;
    std::map<std::string, int64_t> inst;
    std::map<std::string, int> levels;
    int lv = 0, lv_r = 0, carry = 0, loops = 0;
    double secs = 0;
    json parts = json::array(), path = json::array();
    std::string yosys;
    for (auto& arg : inputs) {
      const auto [in, k] = part_arg(arg);
      const json p = load_report(in);
      yosys = p.value("yosys", "");
      total.add(Res::from_json(p["total"]), k);
      for (auto& [b, j] : p["blocks"].items()) {
        blocks[b].add(Res::from_json(j), k);
        inst[b] += j.value("instances", int64_t{0}) * k;
        if (j.contains("lut_levels")) levels[b] = std::max(levels[b], j["lut_levels"].get<int>());
      }
      int l = p["total"].value("lut_levels", 0);
      if (l > lv || path.empty()) {
        path = p.value("critical_path", json::array());
        carry = p["total"].value("carry_on_path", 0);
      }
      lv = std::max(lv, l);
      lv_r = std::max(lv_r, p["total"].value("lut_levels_reg2reg", 0));
      loops += p.value("comb_loops", 0);
      secs += p.value("seconds", 0.0);
      parts.push_back(
          {{"top", p.value("top", "")}, {"seconds", p.value("seconds", 0.0)}, {"command", p.value("command", "")}});
    }
    json r = report_head(yosys, top, family, config, params, "sum of blocks", secs);
    r["parts"] = parts;
    r["missing_blocks"] = missing;  // non-empty: the total is a lower bound
    r["total"] = total.to_json();
    r["total"]["lut_levels"] = lv;
    r["total"]["lut_levels_reg2reg"] = lv_r;
    r["total"]["carry_on_path"] = carry;
    r["comb_loops"] = loops;
    r["critical_path"] = path;
    r["blocks"] = json::object();
    for (auto& [b, res] : blocks) {
      r["blocks"][b] = res.to_json();
      r["blocks"][b]["instances"] = inst[b];
      if (levels.count(b)) r["blocks"][b]["lut_levels"] = levels[b];
    }
    save(out, r);
    if (!quiet) print_report(r, false);
  } else if (*kids) {
    json stat = load_stat(stat_path);
    if (!stat.contains("modules")) fail(fmt::format("{}: no \"modules\"", stat_path));
    std::map<std::string, std::string> mods;  // normalized -> as named
    for (auto& [name, m] : stat["modules"].items()) mods[norm(name)] = name;
    if (!mods.count(norm(top))) fail(fmt::format("{}: module '{}' not found", stat_path, top));
    auto& m = stat["modules"][mods[norm(top)]];
    for (auto& [t, n] : by_type(m).items())
      if (mods.count(norm(t))) fmt::print("{} {}\n", mods[norm(t)], n.get<int64_t>());
  } else if (*show) {
    int bad = 0;
    for (auto& in : inputs) {
      const json r = load_report(in);
      if (r.value("family", "") == "ecp5") {
        sm::synth::print_pnr_report(r, md);
        continue;
      }
      print_report(r, md);
      if (need_bram && r["total"].value("bram36", 0.0) <= 0) {
        fmt::print(stderr, "sm_synth_report: {}: {} has no block RAM but is expected to use it\n", in,
                   r.value("top", ""));
        bad++;
      }
      if (r["total"].value("unmapped", 0) > 0) {
        fmt::print(stderr, "sm_synth_report: {}: {} unmapped Yosys cells\n", in, r["total"]["unmapped"].get<int>());
        bad++;
      }
    }
    return bad ? 1 : 0;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return sm::tools::run_guarded("sm_synth_report", [&] { return run(argc, argv); });
}
