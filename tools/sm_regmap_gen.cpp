// Register map generator: reads rtl/regmap.json (the single source of truth) and writes
// sm_regmap.vh (Verilog localparams and the register tables sm_axil_regs is built from:
// every register's address, the rw fields with their packed host / shadow offsets, the
// constant ro fields; included inside sm_axil_regs), sm_regmap.hpp (C++
// constants and a register table for the test benches and the harness), sm_regvalues.hpp
// (sm::RegValues: the value registers as the C++ members of the model's sm::Regs, with
// their reset values) and registers.md (the documentation committed as
// docs/registers.md); with --defs also the shared definitions of rtl/defs.json:
// sm_defs.vh, sm_defs_check.vh and sm_defs.hpp.
//
// Usage: sm_regmap_gen <regmap.json> <output dir> [--defs defs.json]
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "model/lower_case.hpp"
#include "toolio/sm_cli.hpp"
#include "toolio/sm_json_file.hpp"

namespace {

using nlohmann::json;

// A value that is either a number or the name of a compile-time parameter.
struct Val {
  bool present = false;
  int64_t num = 0;
  std::string param;  // non-empty: value of this parameter
};

struct Field {
  std::string name;
  int lsb = 0;
  int width = 0;
  std::string access = "ro";  // ro, rw, w1c, wp
  Val reset, min, max;
  bool is_signed = false;
  bool shadow = false;
  bool is_const = false;  // ro field that never changes (read back from the generated table)
  std::string desc;
};

struct Reg {
  std::string name;
  uint32_t addr = 0;
  std::string desc;
  std::vector<Field> fields;
};

struct Map {
  std::string title;
  int addr_bits = 16;
  std::vector<std::string> params;
  std::vector<std::string> notes;
  std::vector<Reg> regs;
  // object list
  uint32_t obj_base = 0, obj_size = 0, obj_offset = 0, obj_stride = 0;
  std::string obj_desc;
  Reg obj_header;
  std::vector<Reg> obj_words;
  // grid window
  uint32_t grid_base = 0, grid_size = 0;
  int grid_point_bits = 0;
  std::string grid_desc;
  std::vector<Field> grid_fields;
};

[[noreturn]] void fail(const std::string& m) { throw std::runtime_error(m); }

// The C++ value of each compile-time parameter the map may name ("params"), on an
// sm::HwConfig `hw`: the one translation for the register table's Val::eval and the
// reset values of sm::RegValues.
struct ParamExpr {
  const char* name;
  const char* expr;
};
constexpr ParamExpr kParamExprs[] = {
    {"MAX_WIDTH", "hw.max_width"},      {"MAX_HEIGHT", "hw.max_height"},     {"DISP", "hw.disp"},
    {"MAX_OBJECTS", "hw.max_objects"},  {"MIN_WIDTH", "hw.min_width()"},     {"PU", "hw.levels_per_clock()"},
    {"MIN_HEIGHT", "hw.min_height()"},  {"SPECKLE_ROWS", "hw.speckle_rows"}, {"SPECKLE_MODE", "hw.speckle_mode()"},
    {"PIXEL_RULES", "hw.pixel_rules()"}};

std::string param_expr(const std::string& p) {
  for (const auto& e : kParamExprs)
    if (p == e.name) return e.expr;
  fail("params: " + p + " has no C++ value (kParamExprs in tools/sm_regmap_gen.cpp)");
}

// The values a field's bits can hold (two's complement when signed).
int64_t field_lo(const Field& f) { return f.is_signed ? -(int64_t{1} << (f.width - 1)) : 0; }
int64_t field_hi(const Field& f) {
  return f.is_signed ? (int64_t{1} << (f.width - 1)) - 1 : (int64_t{1} << f.width) - 1;
}

int64_t parse_num(const json& j, const std::string& what) {
  if (j.is_number_integer()) return j.get<int64_t>();
  if (j.is_string()) {
    const auto s = j.get<std::string>();
    try {
      size_t pos = 0;
      const int64_t v = std::stoll(s, &pos, 0);
      if (pos == s.size()) return v;
    } catch (const std::exception&) {
    }
  }
  fail(fmt::format("{}: expected an integer, got {}", what, j.dump()));
}

Val parse_val(const json& j, const std::string& what, const std::vector<std::string>& params) {
  Val v;
  v.present = true;
  if (j.is_string()) {
    const auto s = j.get<std::string>();
    for (const auto& p : params)
      if (s == p) {
        v.param = s;
        return v;
      }
  }
  v.num = parse_num(j, what);
  return v;
}

Field parse_field(const json& j, const std::string& where, const std::vector<std::string>& params, bool need_access) {
  Field f;
  f.name = j.at("name").get<std::string>();
  const auto w = where + "." + f.name;
  f.lsb = static_cast<int>(parse_num(j.at("lsb"), w + ".lsb"));
  f.width = static_cast<int>(parse_num(j.at("width"), w + ".width"));
  if (f.lsb < 0 || f.width < 1 || f.lsb + f.width > 32) fail(w + ": field outside bits 31:0");
  if (need_access) {
    f.access = j.at("access").get<std::string>();
    if (f.access != "ro" && f.access != "rw" && f.access != "w1c" && f.access != "wp")
      fail(w + ": access must be ro, rw, w1c or wp");
    f.reset = parse_val(j.at("reset"), w + ".reset", params);
  }
  if (j.contains("min")) f.min = parse_val(j.at("min"), w + ".min", params);
  if (j.contains("max")) f.max = parse_val(j.at("max"), w + ".max", params);
  if (f.min.present != f.max.present) fail(w + ": min and max go together");
  f.is_signed = j.value("signed", false);
  f.shadow = j.value("shadow", false);
  f.is_const = j.value("const", false);
  if (f.is_const && f.access != "ro") fail(w + ": only ro fields can be const");
  if (f.shadow && f.access != "rw") fail(w + ": only rw fields can be shadowed");
  f.desc = j.value("desc", "");
  return f;
}

void check_overlap(const std::vector<Field>& fs, const std::string& where) {
  uint32_t used = 0;
  for (const auto& f : fs) {
    const uint32_t m = (f.width == 32 ? 0xffffffffu : ((1u << f.width) - 1u)) << f.lsb;
    if (used & m) fail(where + ": field " + f.name + " overlaps another field");
    used |= m;
  }
}

Map parse(const json& j) {
  Map m;
  m.title = j.value("title", "Register map");
  m.addr_bits = static_cast<int>(parse_num(j.at("addr_bits"), "addr_bits"));
  m.params = j.at("params").get<std::vector<std::string>>();
  for (const auto& p : m.params) (void)param_expr(p);  // every parameter has a C++ value
  if (j.contains("notes")) m.notes = j.at("notes").get<std::vector<std::string>>();
  std::set<uint32_t> addrs;
  std::set<std::string> names;
  for (const auto& r : j.at("registers")) {
    Reg reg;
    reg.name = r.at("name").get<std::string>();
    reg.addr = static_cast<uint32_t>(parse_num(r.at("addr"), reg.name + ".addr"));
    reg.desc = r.value("desc", "");
    if (reg.addr % 4) fail(reg.name + ": address not word aligned");
    if (!addrs.insert(reg.addr).second) fail(reg.name + ": address used twice");
    if (!names.insert(reg.name).second) fail(reg.name + ": name used twice");
    for (const auto& f : r.at("fields")) reg.fields.push_back(parse_field(f, reg.name, m.params, true));
    if (reg.fields.empty()) fail(reg.name + ": no fields");
    check_overlap(reg.fields, reg.name);
    for (const auto& f : reg.fields)
      if (f.min.present && reg.fields.size() != 1)
        fail(reg.name + ": a clamped (min/max) field must be the register's only field");
    for (const auto& f : reg.fields) {
      if (!f.min.present) continue;
      // The register file clamps the whole word into a field at bit 0 that holds max.
      if (f.access != "rw" || f.lsb != 0) fail(reg.name + ": a clamped field must be rw at bit 0");
      if (f.is_signed && (!f.min.param.empty() || !f.max.param.empty()))
        fail(reg.name + ": a signed clamped field needs numeric min and max");
      if (f.is_signed && f.width == 32) fail(reg.name + ": a signed clamped field must be narrower than 32 bits");
      if (f.is_signed && (f.min.num < field_lo(f) || f.max.num > field_hi(f)))
        fail(reg.name + ": min..max does not fit the signed field");
      if (!f.is_signed && ((f.min.param.empty() && f.min.num < field_lo(f)) ||
                           (f.max.param.empty() && (f.max.num > field_hi(f) || f.max.num >= (int64_t{1} << 31)))))
        fail(reg.name + ": min..max does not fit the unsigned field");
    }
    for (const auto& f : reg.fields)
      if (f.reset.param.empty() && (f.reset.num < field_lo(f) || f.reset.num > field_hi(f)))
        fail(reg.name + "." + f.name + ": reset value does not fit the field");
    m.regs.push_back(reg);
  }
  const auto& o = j.at("object_list");
  m.obj_base = static_cast<uint32_t>(parse_num(o.at("base"), "object_list.base"));
  m.obj_size = static_cast<uint32_t>(parse_num(o.at("size"), "object_list.size"));
  m.obj_offset = static_cast<uint32_t>(parse_num(o.at("obj_offset"), "object_list.obj_offset"));
  m.obj_stride = static_cast<uint32_t>(parse_num(o.at("obj_stride"), "object_list.obj_stride"));
  m.obj_desc = o.value("desc", "");
  m.obj_header.name = o.at("header").at("name").get<std::string>();
  for (const auto& f : o.at("header").at("fields"))
    m.obj_header.fields.push_back(parse_field(f, m.obj_header.name, m.params, false));
  check_overlap(m.obj_header.fields, m.obj_header.name);
  for (const auto& w : o.at("words")) {
    Reg reg;
    reg.name = w.at("name").get<std::string>();
    reg.addr = static_cast<uint32_t>(parse_num(w.at("offset"), reg.name + ".offset"));
    for (const auto& f : w.at("fields")) reg.fields.push_back(parse_field(f, reg.name, m.params, false));
    check_overlap(reg.fields, reg.name);
    m.obj_words.push_back(reg);
  }
  if (m.obj_stride != 4 * m.obj_words.size()) fail("object_list: obj_stride must be 4 * words");
  const auto& g = j.at("grid_window");
  m.grid_base = static_cast<uint32_t>(parse_num(g.at("base"), "grid_window.base"));
  m.grid_size = static_cast<uint32_t>(parse_num(g.at("size"), "grid_window.size"));
  m.grid_point_bits = static_cast<int>(parse_num(g.at("point_bits"), "grid_window.point_bits"));
  m.grid_desc = g.value("desc", "");
  for (const auto& f : g.at("fields")) m.grid_fields.push_back(parse_field(f, "GRID", m.params, false));
  if ((4u << (m.grid_point_bits + 2)) != m.grid_size) fail("grid_window: size must be 4 * 2^(point_bits + 2)");
  const uint64_t top = uint64_t{1} << m.addr_bits;
  for (const auto& r : m.regs)
    if (r.addr >= m.obj_base || r.addr >= m.grid_base) fail(r.name + ": overlaps a window");
  if (m.obj_base + m.obj_size > m.grid_base || m.grid_base + m.grid_size > top)
    fail("windows overlap or exceed addr_bits");
  return m;
}

std::string hex32(uint64_t v) { return fmt::format("32'h{:08X}", v & 0xffffffffu); }

std::string vval(const Val& v) {
  if (!v.param.empty()) return v.param;
  return fmt::format("{}", v.num);
}

std::string cval(const Val& v) {
  if (!v.param.empty()) return fmt::format("Val{{0, \"{}\"}}", v.param);
  return fmt::format("Val{{{}, nullptr}}", v.num);
}

std::string mdval(const Val& v) {
  if (!v.param.empty()) return v.param;
  if (v.num > 9 || v.num < -9) return fmt::format("0x{:X}", static_cast<uint64_t>(v.num) & 0xffffffffu);
  return fmt::format("{}", v.num);
}

std::string bits(const Field& f) {
  if (f.width == 1) return fmt::format("{}", f.lsb);
  return fmt::format("{}:{}", f.lsb + f.width - 1, f.lsb);
}

// Concatenation (first element in the low bits) of the generated table's elements.
std::string vcat(const std::vector<std::string>& els) {
  std::string r = "{";
  for (size_t i = els.size(); i-- > 0;) r += els[i] + (i ? ", " : "");
  return r + "}";
}

// The tables that make sm_axil_regs register-independent: every register's address, the
// rw fields (kept in one packed host vector and, when shadowed, one packed shadow vector)
// and the constant ro fields. Element i of a table is bits i*W +: W.
void gen_vh_tables(std::ostringstream& o, const Map& m) {
  struct RwRef {
    const Reg* r;
    const Field* f;
  };
  std::vector<RwRef> rw;
  std::vector<RwRef> cst;
  for (const auto& r : m.regs)
    for (const auto& f : r.fields) {
      if (f.access == "rw") rw.push_back({&r, &f});
      if (f.is_const) cst.push_back({&r, &f});
    }
  if (rw.empty() || cst.empty()) fail("the register map needs rw and const fields");
  std::vector<std::string> raddr, rwr;
  for (const auto& r : m.regs) {
    raddr.push_back(fmt::format("SM_{}_ADDR", r.name));
    bool w = false;
    for (const auto& f : r.fields) w = w || f.access != "ro";
    rwr.push_back(w ? "1'b1" : "1'b0");
  }
  o << "// ---- tables (element i at bits i*W +: W)\n";
  o << fmt::format("localparam integer SM_REG_N = {};\n", m.regs.size());
  o << fmt::format("localparam [SM_REG_N*{}-1:0] SM_REG_ADDR = {};\n", m.addr_bits, vcat(raddr));
  o << fmt::format("localparam [SM_REG_N-1:0] SM_REG_WRITABLE = {};  // has rw / w1c / wp fields\n", vcat(rwr));
  // Storage width: a clamped unsigned field holds only 0..max, so it keeps only the bits
  // max needs (WIDTH and HEIGHT at the configured frame size).
  o << "// rw fields: SW bits stored at OFF of the host vector (SOFF of the shadow vector)\n";
  std::string prev_off = "32'd0", prev_soff = "32'd0";
  for (const auto& x : rw) {
    const auto p = fmt::format("SM_{}_{}", x.r->name, x.f->name);
    std::string sw = fmt::format("32'd{}", x.f->width);
    if (x.f->min.present && !x.f->is_signed) {
      if (x.f->max.param.empty()) {
        int b = 1;
        while ((int64_t{1} << b) <= x.f->max.num) ++b;
        sw = fmt::format("32'd{}", b < x.f->width ? b : x.f->width);
      } else {
        sw = fmt::format("(($clog2({0} + 1) < {1}) ? (($clog2({0} + 1) < 1) ? 32'd1 : $clog2({0} + 1)) : 32'd{1})",
                         x.f->max.param, x.f->width);
      }
    }
    o << fmt::format("localparam [31:0] {}_SW = {};\n", p, sw);
    o << fmt::format("localparam [31:0] {}_OFF = {};\n", p, prev_off);
    prev_off = fmt::format("{0}_OFF + {0}_SW", p);
    if (x.f->shadow) {
      o << fmt::format("localparam [31:0] {}_SOFF = {};\n", p, prev_soff);
      prev_soff = fmt::format("{0}_SOFF + {0}_SW", p);
    }
  }
  o << fmt::format("localparam integer SM_RW_BITS = {};\n", prev_off);
  o << fmt::format("localparam integer SM_SHADOW_BITS = {};\n", prev_soff);
  std::vector<std::string> a, lsb, w, sw, off, soff, rst, mn, mx, cl, sg, sh, cidx;
  int nclamp = 0;
  for (const auto& x : rw) {
    const auto p = fmt::format("SM_{}_{}", x.r->name, x.f->name);
    a.push_back(fmt::format("SM_{}_ADDR", x.r->name));
    lsb.push_back(fmt::format("32'd{}", x.f->lsb));
    w.push_back(fmt::format("32'd{}", x.f->width));
    sw.push_back(fmt::format("{}_SW", p));
    off.push_back(fmt::format("{}_OFF", p));
    soff.push_back(x.f->shadow ? fmt::format("{}_SOFF", p) : "32'd0");
    rst.push_back(fmt::format("{}_RESET", p));
    mn.push_back(x.f->min.present ? fmt::format("{}_MIN[31:0]", p) : "32'd0");
    mx.push_back(x.f->min.present ? fmt::format("{}_MAX[31:0]", p) : "32'd0");
    cl.push_back(x.f->min.present ? "1'b1" : "1'b0");
    cidx.push_back(fmt::format("32'd{}", x.f->min.present ? nclamp++ : 0));
    sg.push_back(x.f->is_signed ? "1'b1" : "1'b0");
    sh.push_back(x.f->shadow ? "1'b1" : "1'b0");
  }
  if (nclamp == 0) fail("the register map needs a clamped field");
  o << fmt::format("localparam integer SM_RW_N = {};\n", rw.size());
  o << fmt::format("localparam integer SM_CLAMP_N = {};  // CIDX: index among the clamped fields\n", nclamp);
  o << fmt::format("localparam [SM_RW_N*{}-1:0] SM_RW_ADDR = {};\n", m.addr_bits, vcat(a));
  for (const auto& [n, v] : {std::pair<const char*, const std::vector<std::string>*>{"LSB", &lsb},
                             {"W", &w},
                             {"SW", &sw},
                             {"OFF", &off},
                             {"SOFF", &soff},
                             {"RESET", &rst},
                             {"MIN", &mn},
                             {"MAX", &mx},
                             {"CIDX", &cidx}})
    o << fmt::format("localparam [SM_RW_N*32-1:0] SM_RW_{} = {};\n", n, vcat(*v));
  o << fmt::format("localparam [SM_RW_N-1:0] SM_RW_CLAMP = {};\n", vcat(cl));
  o << fmt::format("localparam [SM_RW_N-1:0] SM_RW_SIGNED = {};\n", vcat(sg));
  o << fmt::format("localparam [SM_RW_N-1:0] SM_RW_SHADOW = {};\n", vcat(sh));
  std::vector<std::string> ca, cv;
  o << "// const ro fields: the register word each contributes (a parameter is cut to its field)\n";
  for (const auto& x : cst) {
    const auto p = fmt::format("SM_{}_{}", x.r->name, x.f->name);
    ca.push_back(fmt::format("SM_{}_ADDR", x.r->name));
    cv.push_back(p + "_WORD");
    const uint32_t mask = x.f->width == 32 ? 0xffffffffu : (1u << x.f->width) - 1u;
    o << fmt::format("localparam [31:0] {0}_WORD = ({0}_RESET & 32'h{1:X}) << {2};\n", p, mask, x.f->lsb);
  }
  o << fmt::format("localparam integer SM_CONST_N = {};\n", cst.size());
  o << fmt::format("localparam [SM_CONST_N*{}-1:0] SM_CONST_ADDR = {};\n", m.addr_bits, vcat(ca));
  o << fmt::format("localparam [SM_CONST_N*32-1:0] SM_CONST_VALUE = {};\n", vcat(cv));
}

std::string gen_vh(const Map& m) {
  std::ostringstream o;
  o << "// Generated by tools/sm_regmap_gen from rtl/regmap.json -- do not edit.\n"
       "// Included inside sm_axil_regs (uses its parameters "
    << fmt::format("{}", fmt::join(m.params, ", ")) << ").\n";
  o << fmt::format("localparam SM_ADDR_BITS = {};\n", m.addr_bits);
  for (const auto& r : m.regs) {
    o << fmt::format("localparam [{}:0] SM_{}_ADDR = {}'h{:X};\n", m.addr_bits - 1, r.name, m.addr_bits, r.addr);
    for (const auto& f : r.fields) {
      const auto p = fmt::format("SM_{}_{}", r.name, f.name);
      o << fmt::format("localparam {}_LSB = {};\n", p, f.lsb);
      o << fmt::format("localparam {}_W = {};\n", p, f.width);
      if (f.reset.param.empty())
        o << fmt::format("localparam [31:0] {}_RESET = {};\n", p, hex32(static_cast<uint64_t>(f.reset.num)));
      else
        o << fmt::format("localparam [31:0] {}_RESET = {};\n", p, f.reset.param);
      if (f.min.present) {
        o << fmt::format("localparam integer {}_MIN = {};\n", p, vval(f.min));
        o << fmt::format("localparam integer {}_MAX = {};\n", p, vval(f.max));
      }
    }
  }
  gen_vh_tables(o, m);
  o << fmt::format("localparam [{}:0] SM_OBJ_BASE = {}'h{:X};\n", m.addr_bits - 1, m.addr_bits, m.obj_base);
  o << fmt::format("localparam SM_OBJ_SIZE = {};\n", m.obj_size);
  o << fmt::format("localparam SM_OBJ_FIRST_IDX = {};  // word index of object 0\n", m.obj_offset / 4);
  o << fmt::format("localparam SM_OBJ_WORDS = {};  // words per object\n", m.obj_stride / 4);
  o << fmt::format("localparam [{}:0] SM_GRID_BASE = {}'h{:X};\n", m.addr_bits - 1, m.addr_bits, m.grid_base);
  o << fmt::format("localparam SM_GRID_SIZE = {};\n", m.grid_size);
  o << fmt::format("localparam SM_GRID_POINT_BITS = {};\n", m.grid_point_bits);
  return o.str();
}

std::string access_enum(const std::string& a) {
  if (a == "rw") return "Access::kRW";
  if (a == "w1c") return "Access::kW1C";
  if (a == "wp") return "Access::kWP";
  return "Access::kRO";
}

// A C++ string literal of s.
std::string cpp_string(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o + "\"";
}

// A value register: one rw, shadowed field named VALUE (the pipeline's numeric
// parameters). Each is the sm::RegValues member of the register's name in lower case.
bool is_value_reg(const Reg& r) {
  return r.fields.size() == 1 && r.fields[0].name == "VALUE" && r.fields[0].access == "rw" && r.fields[0].shadow;
}

// The C++ type of a value register's member: bool for one bit, int when a compile-time
// parameter bounds the field (WIDTH, HEIGHT), else the narrowest (u)int8/16/32_t.
std::string member_type(const Field& f) {
  if (f.width == 1) return "bool";
  if (!f.min.param.empty() || !f.max.param.empty() || !f.reset.param.empty()) return "int";
  return fmt::format("{}int{}_t", f.is_signed ? "" : "u", f.width <= 8 ? 8 : f.width <= 16 ? 16 : 32);
}

// The C++ value of v on the HwConfig expression `hw` ("hw" or "HwConfig{}"), as type t.
std::string member_value(const Val& v, const std::string& t, const std::string& hw) {
  if (!v.param.empty()) {
    std::string e = param_expr(v.param);  // "hw.<member>"
    e.replace(0, 2, hw);
    return t == "bool" ? e + " != 0" : e;
  }
  if (t == "bool") return v.num ? "true" : "false";
  if (t == "uint32_t") return fmt::format("{}u", v.num);
  return fmt::format("{}", v.num);
}

// `text` as // comment lines of at most `cols` columns, each starting with `indent`.
void wrap_comment(std::ostringstream& o, const std::string& indent, const std::string& text, size_t cols = 100) {
  std::istringstream words(text);
  std::string w, line;
  while (words >> w) {
    if (!line.empty() && indent.size() + 3 + line.size() + 1 + w.size() > cols) {
      o << indent << "// " << line << "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) o << indent << "// " << line << "\n";
}

// sm_regvalues.hpp: the value registers as C++ members (sm::RegValues, the base of the
// model's sm::Regs), so that a register added to regmap.json is a member of sm::Regs,
// a key of the tools' register file, an option and a word of the harness's AXI-Lite
// writer (all expand SM_REGMAP_VALUE_REGS over these members) with no hand edit.
std::string gen_values_hpp(const Map& m) {
  std::ostringstream o;
  o << "// Generated by tools/sm_regmap_gen from rtl/regmap.json -- do not edit.\n"
       "// Included by sm_types.hpp after sm::HwConfig (the parameter-dependent reset values use it);\n"
       "// include sm_types.hpp, not this file.\n"
       "#pragma once\n\n#include <cstdint>\n\nnamespace sm {\n\n";
  wrap_comment(o, "",
               "The value registers of rtl/regmap.json (one rw, shadowed VALUE field; SM_REGMAP_VALUE_REGS in "
               "sm_regmap.hpp), one member each, named after the register in lower case. A member is bool for a "
               "one-bit field, int when a compile-time parameter bounds the field, else the narrowest "
               "(u)int8/16/32_t of the field. The initialisers are the reset values for HwConfig{}; "
               "set_reset_values(hw) sets those of another configuration. sm::Regs adds the other run-time "
               "registers (grids, SW_TABLE).");
  o << "struct RegValues {\n";
  std::ostringstream set;
  for (const auto& r : m.regs) {
    if (!is_value_reg(r)) continue;
    const Field& f = r.fields[0];
    const std::string t = member_type(f), member = sm::lower_case(r.name);
    const std::string range = f.min.present ? fmt::format("{}..{}", vval(f.min), vval(f.max)) : "";
    const std::string head =
        fmt::format("{} (0x{:03X}, {} bit{}{}{}, reset {}):", r.name, r.addr, f.width, f.width == 1 ? "" : "s",
                    f.is_signed ? " signed" : "", range.empty() ? "" : ", " + range, vval(f.reset));
    std::string text = head + " " + r.desc;
    if (!f.desc.empty() && f.desc != range) text += " " + f.desc;
    wrap_comment(o, "  ", text);
    o << fmt::format("  {} {} = {};\n", t, member, member_value(f.reset, t, "HwConfig{}"));
    set << fmt::format("  {} = {};\n", member, member_value(f.reset, t, "hw"));
  }
  o << "  // Every member to its register's reset value at the parameters hw.\n"
       "  void set_reset_values(const HwConfig& hw);\n};\n\n";
  o << "inline void RegValues::set_reset_values(const HwConfig& hw) {\n  (void)hw;\n" << set.str() << "}\n\n";
  o << "}  // namespace sm\n";
  return o.str();
}

std::string gen_hpp(const Map& m) {
  std::ostringstream o;
  std::string eval;
  for (const auto& p : m.params)
    eval += fmt::format("    if (!std::strcmp(param, \"{}\")) return {};\n", p, param_expr(p));
  std::string head = R"(// Generated by tools/sm_regmap_gen from rtl/regmap.json -- do not edit.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "sm_types.hpp"

namespace sm::regmap {

enum class Access { kRO, kRW, kW1C, kWP };  // wp: write-1 pulse, reads 0

// A number or the value of a compile-time parameter.
struct Val {
  int64_t num;
  const char* param;
  int64_t eval(const HwConfig& hw) const {
    if (!param) return num;
@EVAL@    throw std::invalid_argument(std::string("regmap: unknown parameter ") + param);
  }
};

struct Field {
  const char* name;
  int lsb;
  int width;
  Access access;
  Val reset;
  bool clamped;  // numeric register: the whole word saturates to min..max
  Val min;
  Val max;
  bool is_signed;
  bool shadow;  // copied to the pipeline at frame_start
  uint32_t mask() const { return (width == 32 ? 0xffffffffu : ((1u << width) - 1u)) << lsb; }
};

struct Reg {
  const char* name;
  uint32_t addr;
  int first_field;  // index into fields()
  int num_fields;
  const char* desc;  // the register's description (tools' help texts)
};

)";
  head.replace(head.find("@EVAL@"), 6, eval);
  o << head;
  o << fmt::format("constexpr int kAddrBits = {};\n\n", m.addr_bits);
  o << "// Register byte addresses.\n";
  for (const auto& r : m.regs) o << fmt::format("constexpr uint32_t k{} = 0x{:03X};\n", r.name, r.addr);
  o << "\n// Field positions: k<REG>_<FIELD>_LSB / _W; _RESET where the reset value is a number.\n";
  for (const auto& r : m.regs)
    for (const auto& f : r.fields) {
      o << fmt::format("constexpr int k{0}_{1}_LSB = {2};\nconstexpr int k{0}_{1}_W = {3};\n", r.name, f.name, f.lsb,
                       f.width);
      if (f.reset.param.empty())
        o << fmt::format("constexpr int64_t k{}_{}_RESET = {};\n", r.name, f.name, f.reset.num);
    }
  size_t nf = 0;
  for (const auto& r : m.regs) nf += r.fields.size();
  o << fmt::format("\ninline const std::array<Field, {}>& fields() {{\n  static const std::array<Field, {}> f{{{{\n",
                   nf, nf);
  for (const auto& r : m.regs)
    for (const auto& f : r.fields)
      o << fmt::format("      {{\"{}.{}\", {}, {}, {}, {}, {}, {}, {}, {}, {}}},\n", r.name, f.name, f.lsb, f.width,
                       access_enum(f.access), cval(f.reset), f.min.present ? "true" : "false", cval(f.min), cval(f.max),
                       f.is_signed ? "true" : "false", f.shadow ? "true" : "false");
  o << "  }};\n  return f;\n}\n";
  o << fmt::format("\ninline const std::array<Reg, {}>& registers() {{\n  static const std::array<Reg, {}> r{{{{\n",
                   m.regs.size(), m.regs.size());
  int fi = 0;
  for (const auto& r : m.regs) {
    o << fmt::format("      {{\"{}\", 0x{:03X}, {}, {}, {}}},\n", r.name, r.addr, fi, r.fields.size(),
                     cpp_string(r.desc));
    fi += static_cast<int>(r.fields.size());
  }
  o << "  }};\n  return r;\n}\n\n";
  // The value registers, each the sm::RegValues (sm::Regs) member of the register's name in
  // lower case (sm_regvalues.hpp), so the C++ lists of them (the AXI-Lite writer, the
  // register file's keys, the tests) expand this one macro.
  o << "// The pipeline's value registers (one rw, shadowed VALUE field), each the sm::Regs member\n"
       "// of its name in lower case (sm::RegValues, sm_regvalues.hpp): X(NAME, member). Expanded\n"
       "// wherever C++ lists them.\n"
       "#define SM_REGMAP_VALUE_REGS(X)";
  for (const auto& r : m.regs)
    if (is_value_reg(r)) o << fmt::format(" \\\n  X({}, {})", r.name, sm::lower_case(r.name));
  o << "\n\n";
  o << "// Object list window (read through the object block's read port).\n";
  o << fmt::format("constexpr uint32_t kObjBase = 0x{:X};\nconstexpr uint32_t kObjSize = 0x{:X};\n", m.obj_base,
                   m.obj_size);
  o << fmt::format("constexpr uint32_t kObjFirstIdx = {};  // word index of object 0\n", m.obj_offset / 4);
  o << fmt::format("constexpr uint32_t kObjWords = {};  // words per object\n", m.obj_stride / 4);
  for (const auto& f : m.obj_header.fields)
    o << fmt::format("constexpr int k{0}_{1}_LSB = {2};\nconstexpr int k{0}_{1}_W = {3};\n", m.obj_header.name, f.name,
                     f.lsb, f.width);
  for (size_t w = 0; w < m.obj_words.size(); ++w) {
    o << fmt::format("constexpr uint32_t k{}_WORD = {};\n", m.obj_words[w].name, m.obj_words[w].addr / 4);
    for (const auto& f : m.obj_words[w].fields)
      o << fmt::format("constexpr int k{0}_{1}_LSB = {2};\nconstexpr int k{0}_{1}_W = {3};\n", m.obj_words[w].name,
                       f.name, f.lsb, f.width);
  }
  o << "// Byte address of word `word` of object i; of the header for obj_header_addr().\n";
  o << "constexpr uint32_t obj_header_addr() { return kObjBase; }\n";
  o << "constexpr uint32_t obj_addr(int i, int word) {\n"
       "  return kObjBase + 4u * (kObjFirstIdx + kObjWords * static_cast<uint32_t>(i) + "
       "static_cast<uint32_t>(word));\n}\n\n";
  o << "// Rectification grid window: address = base + 4 * {cam, bank, point}.\n";
  o << fmt::format("constexpr uint32_t kGridBase = 0x{:X};\nconstexpr uint32_t kGridSize = 0x{:X};\n", m.grid_base,
                   m.grid_size);
  o << fmt::format("constexpr int kGridPointBits = {};\n", m.grid_point_bits);
  o << "constexpr uint32_t grid_addr(int cam, int bank, int point) {\n"
       "  return kGridBase + 4u * ((static_cast<uint32_t>(cam) << (kGridPointBits + 1)) |\n"
       "                           (static_cast<uint32_t>(bank) << kGridPointBits) |\n"
       "                           static_cast<uint32_t>(point));\n}\n";
  o << "// Grid word: {sy, sx}, each signed Q.5.\n"
       "constexpr uint32_t grid_word(int16_t sx, int16_t sy) {\n"
       "  return (static_cast<uint32_t>(static_cast<uint16_t>(sy)) << 16) | static_cast<uint16_t>(sx);\n}\n";
  o << "constexpr int grid_points(const HwConfig& hw) {\n"
       "  return ((hw.max_width + 15) / 16 + 1) * ((hw.max_height + 15) / 16 + 1);\n}\n\n";
  o << "}  // namespace sm::regmap\n";
  return o.str();
}

std::string md_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '|')
      r += "\\|";
    else
      r += c;
  }
  return r;
}

void md_fields(std::ostringstream& o, const std::vector<Field>& fs, bool with_access) {
  if (with_access) {
    o << "| bits | field | access | reset | range | description |\n|---|---|---|---|---|---|\n";
    for (const auto& f : fs) {
      std::string range = f.min.present ? fmt::format("{}..{}", mdval(f.min), mdval(f.max)) : "";
      if (f.is_signed) range += " (signed)";
      std::string acc = f.access;
      if (f.shadow) acc += ", shadow";
      o << fmt::format("| {} | {} | {} | {} | {} | {} |\n", bits(f), f.name, acc, mdval(f.reset), range,
                       md_escape(f.desc));
    }
  } else {
    o << "| bits | field | description |\n|---|---|---|\n";
    for (const auto& f : fs) o << fmt::format("| {} | {} | {} |\n", bits(f), f.name, md_escape(f.desc));
  }
  o << "\n";
}

std::string gen_md(const Map& m) {
  std::ostringstream o;
  o << "# " << m.title << "\n\n";
  o << "<!-- Generated by tools/sm_regmap_gen from rtl/regmap.json -- do not edit; the ctest "
       "regmap_doc_current checks that this file is up to date. -->\n\n";
  o << fmt::format(
      "Address width {} bits (byte addresses). Access: `ro` read-only, `rw` read/write, "
      "`w1c` write 1 to clear, `wp` write 1 for a one-clock pulse (reads 0); `shadow` "
      "fields reach the pipeline at the next frame start.\n\n",
      m.addr_bits);
  for (const auto& n : m.notes) o << "- " << n << "\n";
  o << "\n## Summary\n\n| address | register | description |\n|---|---|---|\n";
  for (const auto& r : m.regs) o << fmt::format("| 0x{:04X} | {} | {} |\n", r.addr, r.name, md_escape(r.desc));
  o << fmt::format("| 0x{:04X}..0x{:04X} | object list | read-only window |\n", m.obj_base,
                   m.obj_base + m.obj_size - 1);
  o << fmt::format("| 0x{:04X}..0x{:04X} | grid window | write-only window |\n", m.grid_base,
                   m.grid_base + m.grid_size - 1);
  o << "\n## Registers\n\n";
  for (const auto& r : m.regs) {
    o << fmt::format("### {} (0x{:04X})\n\n{}\n\n", r.name, r.addr, r.desc);
    md_fields(o, r.fields, true);
  }
  o << fmt::format("## Object list (0x{:04X}..0x{:04X})\n\n{}\n\n", m.obj_base, m.obj_base + m.obj_size - 1,
                   m.obj_desc);
  o << fmt::format("### {} (0x{:04X})\n\n", m.obj_header.name, m.obj_base);
  md_fields(o, m.obj_header.fields, false);
  for (const auto& w : m.obj_words) {
    o << fmt::format("### {} (0x{:04X} + 0x{:X} * i + 0x{:X})\n\n", w.name, m.obj_base + m.obj_offset, m.obj_stride,
                     w.addr);
    md_fields(o, w.fields, false);
  }
  o << fmt::format("## Rectification grid window (0x{:04X}..0x{:04X})\n\n{}\n\n", m.grid_base,
                   m.grid_base + m.grid_size - 1, m.grid_desc);
  md_fields(o, m.grid_fields, false);
  return o.str();
}

// ---------------------------------------------------------------- definitions (rtl/defs.json)
// The sideband layout, the sm_top parameter limits and the rectification grid geometry,
// one description for the Verilog macros (sm_defs.vh), the elaboration checks of sm_top
// (sm_defs_check.vh) and the C++ constants (sm_defs.hpp).

struct Limit {
  std::string name, parity, desc;  // parity: "", "even" or "odd"
  int64_t min = 0, max = 0;
};

struct Defs {
  int side_w = 0;
  std::string side_desc;
  std::vector<Field> side;
  std::vector<Limit> limits;
  int grid_shift = 0, grid_frac = 0;
  std::string grid_desc;
  struct Constant {
    std::string name, desc;
    int64_t value = 0;
  };
  std::vector<Constant> constants;  // named numbers both languages use
};

// AGG_PIPE_BEATS -> AggPipeBeats (the C++ constant kAggPipeBeats)
std::string camel(const std::string& upper) {
  std::string o;
  bool up = true;
  for (char c : upper) {
    if (c == '_') {
      up = true;
      continue;
    }
    o += up ? c : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    up = false;
  }
  return o;
}

Defs parse_defs(const json& j) {
  Defs d;
  const auto& sb = j.at("sideband");
  d.side_w = static_cast<int>(parse_num(sb.at("width"), "sideband.width"));
  d.side_desc = sb.value("desc", "");
  if (d.side_w < 1 || d.side_w > 8) fail("sideband.width must be 1..8");
  for (const auto& f : sb.at("fields")) {
    d.side.push_back(parse_field(f, "sideband", {}, false));
    if (d.side.back().lsb + d.side.back().width > d.side_w)
      fail("sideband." + d.side.back().name + ": outside the sideband");
  }
  check_overlap(d.side, "sideband");
  for (const auto& l : j.at("limits")) {
    Limit x;
    x.name = l.at("name").get<std::string>();
    x.min = parse_num(l.at("min"), "limits." + x.name + ".min");
    x.max = parse_num(l.at("max"), "limits." + x.name + ".max");
    x.parity = l.value("parity", "");
    x.desc = l.value("desc", "");
    if (x.min > x.max) fail("limits." + x.name + ": min above max");
    if (!x.parity.empty() && x.parity != "even" && x.parity != "odd")
      fail("limits." + x.name + ": parity must be even or odd");
    d.limits.push_back(x);
  }
  const auto& g = j.at("grid");
  d.grid_shift = static_cast<int>(parse_num(g.at("shift"), "grid.shift"));
  d.grid_frac = static_cast<int>(parse_num(g.at("frac"), "grid.frac"));
  d.grid_desc = g.value("desc", "");
  if (d.grid_shift < 1 || d.grid_shift > 8 || d.grid_frac < 0 || d.grid_frac > 8) fail("grid: shift 1..8, frac 0..8");
  for (const auto& c : j.value("constants", json::array())) {
    Defs::Constant x;
    x.name = c.at("name").get<std::string>();
    x.value = parse_num(c.at("value"), "constants." + x.name);
    x.desc = c.value("desc", "");
    if (x.name.empty() || x.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string::npos)
      fail("constants: name '" + x.name + "' must be upper case");
    d.constants.push_back(x);
  }
  return d;
}

std::string limit_text(const Limit& l) {
  return fmt::format("{}{}..{}", l.parity.empty() ? "" : l.parity + ", ", l.min, l.max);
}

std::string gen_defs_vh(const Defs& d) {
  std::ostringstream o;
  o << "// Generated by tools/sm_regmap_gen from rtl/defs.json -- do not edit.\n"
       "// Macros, so that port lists can use them too; guarded, since every RTL file that uses\n"
       "// them includes this file.\n"
       "`ifndef SM_DEFS_VH\n`define SM_DEFS_VH\n\n";
  o << "// " << d.side_desc << "\n";
  o << fmt::format("`define SM_SIDE_W {}\n", d.side_w);
  for (const auto& f : d.side) {
    if (f.width == 1)
      o << fmt::format("`define SM_SIDE_{} {}  // {}\n", f.name, f.lsb, f.desc);
    else
      o << fmt::format("`define SM_SIDE_{} {}:{}  // {}\n`define SM_SIDE_{}_LSB {}\n`define SM_SIDE_{}_W {}\n", f.name,
                       f.lsb + f.width - 1, f.lsb, f.desc, f.name, f.lsb, f.name, f.width);
  }
  o << "\n// Legal range of each sm_top parameter (checked by sm_defs_check.vh in sm_top).\n";
  for (const auto& l : d.limits)
    o << fmt::format("`define SM_{0}_MIN {1}\n`define SM_{0}_MAX {2}  // {3}\n", l.name, l.min, l.max, l.desc);
  o << "\n// Bits of a counter or coordinate that holds 0..n.\n"
       "`define SM_COUNT_W(n) $clog2((n) + 1)\n";
  if (!d.constants.empty()) o << "\n";
  for (const auto& c : d.constants) o << fmt::format("`define SM_{} {}  // {}\n", c.name, c.value, c.desc);
  o << "\n// An illegal parameter combination: inside a generate region,\n"
       "//   `SM_BAD_PARAM(g_bad_x, <illegal when true>, (\"sm_block: X (%0d) must be ...\", X))\n"
       "// makes Yosys stop at elaboration and Verilator and Icarus stop at time 0.\n"
       "`define SM_BAD_PARAM(label, bad, msg) if (bad) begin : label initial $error msg; end\n";
  o << "\n// " << d.grid_desc << "\n";
  o << fmt::format("`define SM_GRID_SHIFT {}\n`define SM_GRID_FRAC {}\n", d.grid_shift, d.grid_frac);
  o << "// grid points along an axis of n pixels, and the address bits of that axis (at least 2)\n"
       "`define SM_GRID_PTS(n) ((((n) + (1 << `SM_GRID_SHIFT) - 1) >> `SM_GRID_SHIFT) + 1)\n"
       "`define SM_GRID_AB(n) (($clog2(`SM_GRID_PTS(n)) < 2) ? 2 : $clog2(`SM_GRID_PTS(n)))\n";
  o << "\n`endif\n";
  return o.str();
}

std::string gen_defs_check_vh(const Defs& d) {
  std::ostringstream o;
  o << "// Generated by tools/sm_regmap_gen from rtl/defs.json -- do not edit.\n"
       "// Elaboration checks of sm_top's parameters, included inside sm_top.\n"
       "generate\n";
  for (const auto& l : d.limits) {
    const std::string lower = sm::lower_case(l.name);
    std::string cond = fmt::format("{0} < `SM_{0}_MIN || {0} > `SM_{0}_MAX", l.name);
    if (l.parity == "even") cond += fmt::format(" || {} % 2 != 0", l.name);
    if (l.parity == "odd") cond += fmt::format(" || {} % 2 != 1", l.name);
    o << fmt::format("  `SM_BAD_PARAM(g_bad_{}, {},\n                (\"sm_top: {} (%0d) must be {}\", {}))\n", lower,
                     cond, l.name, limit_text(l), l.name);
  }
  o << "endgenerate\n";
  return o.str();
}

std::string gen_defs_hpp(const Defs& d) {
  std::ostringstream o;
  o << "// Generated by tools/sm_regmap_gen from rtl/defs.json -- do not edit.\n"
       "#pragma once\n\n#include <array>\n#include <cstdint>\n\nnamespace sm::defs {\n\n";
  o << "// " << d.side_desc << "\n";
  o << fmt::format("constexpr int kSideW = {};\n", d.side_w);
  for (const auto& f : d.side) {
    o << fmt::format(
        "constexpr int kSide{0}Lsb = {1};  // {2}\nconstexpr int kSide{0}W = {3};\n"
        "constexpr uint8_t kSide{0} = 0x{4:X};  // mask\n",
        camel(f.name), f.lsb, f.desc, f.width, ((1u << f.width) - 1u) << f.lsb);
  }
  o << "\n// Legal range of each sm_top parameter (HwConfig::validate() checks this table).\n"
       "enum class Parity { kAny, kEven, kOdd };\n"
       "struct Limit {\n  const char* name;\n  int min, max;\n  Parity parity;\n  const char* desc;\n};\n";
  o << fmt::format("constexpr std::array<Limit, {}> kLimits{{{{\n", d.limits.size());
  for (const auto& l : d.limits)
    o << fmt::format("    {{\"{}\", {}, {}, Parity::{}, \"{}\"}},\n", l.name, l.min, l.max,
                     l.parity == "even"  ? "kEven"
                     : l.parity == "odd" ? "kOdd"
                                         : "kAny",
                     l.desc);
  o << "}};\n";
  o << "constexpr const Limit& limit(const char* name) {\n"
       "  for (const auto& l : kLimits) {\n"
       "    const char *a = l.name, *b = name;\n"
       "    while (*a && *a == *b) ++a, ++b;\n"
       "    if (*a == *b) return l;\n"
       "  }\n"
       "  return kLimits[0];  // not reached for a listed name (a constant expression fails first)\n"
       "}\n";
  o << "\n// Bits of a counter or coordinate that holds 0..n (`SM_COUNT_W).\n"
       "constexpr int count_w(int n) {\n  int b = 0;\n  while ((1 << b) < n + 1) ++b;\n  return b;\n}\n";
  o << "\n// " << d.grid_desc << "\n";
  o << fmt::format("constexpr int kGridShift = {};\nconstexpr int kGridFrac = {};\n", d.grid_shift, d.grid_frac);
  o << "constexpr int grid_pts(int n) { return ((n + (1 << kGridShift) - 1) >> kGridShift) + 1; }  // `SM_GRID_PTS\n";
  if (!d.constants.empty()) o << "\n";
  for (const auto& c : d.constants)
    o << fmt::format("constexpr int k{} = {};  // `SM_{}: {}\n", camel(c.name), c.value, c.name, c.desc);
  o << "\n}  // namespace sm::defs\n";
  return o.str();
}

void write_if_changed(const std::string& path, const std::string& text) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::ostringstream cur;
      cur << in.rdbuf();
      if (cur.str() == text) return;  // keep the time stamp: no needless rebuilds
    }
  }
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) fail("cannot write " + path);
}

int run(int argc, char** argv) {
  CLI::App app{"Generate sm_regmap.vh, sm_regmap.hpp, sm_regvalues.hpp and registers.md from regmap.json"};
  std::string in_path, out_dir, defs_path;
  app.add_option("json", in_path, "register map (rtl/regmap.json)")->required();
  app.add_option("outdir", out_dir, "output directory")->required();
  app.add_option("--defs", defs_path,
                 "definitions (rtl/defs.json): also write sm_defs.vh, sm_defs_check.vh and sm_defs.hpp")
      ->check(CLI::ExistingFile);
  if (const auto rc = sm::tools::parse_cli(app, argc, argv)) return *rc;
  // one JSON value per file, no key twice (toolio/sm_json_file.hpp); errors name the file
  Map m;
  try {
    m = parse(sm::tools::read_json_file(in_path));
  } catch (const json::exception& e) {
    fail(fmt::format("{}: missing or malformed entry: {}", in_path, e.what()));
  } catch (const sm::tools::JsonFileError&) {
    throw;
  } catch (const std::exception& e) {
    fail(fmt::format("{}: {}", in_path, e.what()));
  }
  write_if_changed(out_dir + "/sm_regmap.vh", gen_vh(m));
  write_if_changed(out_dir + "/sm_regmap.hpp", gen_hpp(m));
  write_if_changed(out_dir + "/sm_regvalues.hpp", gen_values_hpp(m));
  write_if_changed(out_dir + "/registers.md", gen_md(m));
  if (!defs_path.empty()) {
    Defs d;
    try {
      d = parse_defs(sm::tools::read_json_file(defs_path));
    } catch (const json::exception& e) {
      fail(fmt::format("{}: missing or malformed entry: {}", defs_path, e.what()));
    } catch (const sm::tools::JsonFileError&) {
      throw;
    } catch (const std::exception& e) {
      fail(fmt::format("{}: {}", defs_path, e.what()));
    }
    write_if_changed(out_dir + "/sm_defs.vh", gen_defs_vh(d));
    write_if_changed(out_dir + "/sm_defs_check.vh", gen_defs_check_vh(d));
    write_if_changed(out_dir + "/sm_defs.hpp", gen_defs_hpp(d));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return sm::tools::run_guarded("sm_regmap_gen", [&] { return run(argc, argv); });
}
