#include "sm_regs_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "sm_io.hpp"
#include "sm_regmap.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace sm::tools {

bool RegsFile::has(const std::string& key) const { return std::find(keys.begin(), keys.end(), key) != keys.end(); }

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

using Set = std::function<void(int64_t)>;

// Setters of the run-time registers, by register name: every register whose fields are
// all rw and shadowed (the pipeline parameters), except CONTROL (not a parameter).
std::map<std::string, Set> register_setters(Regs& r) {
  auto sw_word = [&r](int half) {
    return [&r, half](int64_t v) {
      for (int k = 0; k < 16; ++k) r.sw_table[16 * half + k] = static_cast<uint8_t>((v >> (2 * k)) & 3);
    };
  };
  // the value registers: the sm::Regs member of the register's name
  std::map<std::string, Set> set{{"SW_TABLE0", sw_word(0)}, {"SW_TABLE1", sw_word(1)}};
#define SM_X(NAME, member) set[#NAME] = [&r](int64_t v) { r.member = static_cast<decltype(r.member)>(v); };
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  return set;
}

struct Range {
  int64_t lo, hi;
};

// The register's one field and its range at this configuration.
Range register_range(const regmap::Reg& reg, const HwConfig& hw) {
  const regmap::Field& f = regmap::fields()[static_cast<size_t>(reg.first_field)];
  if (f.clamped) return {f.min.eval(hw), f.max.eval(hw)};
  return {0, f.width == 32 ? int64_t{0xffffffff} : (int64_t{1} << f.width) - 1};
}

const regmap::Reg* find_register(const std::string& name) {
  for (const auto& g : regmap::registers())
    if (name == g.name) return &g;
  return nullptr;
}

}  // namespace

std::vector<ValueRegister> value_registers() {
  std::vector<ValueRegister> v;
  Regs scratch;
  for (const auto& [name, set] : register_setters(scratch)) {
    (void)set;
    const regmap::Reg* reg = find_register(name);
    v.push_back({name, reg->desc, reg->addr});
  }
  std::sort(v.begin(), v.end(), [](const ValueRegister& a, const ValueRegister& b) { return a.addr < b.addr; });
  return v;
}

int64_t register_value(const std::string& name, const Regs& r) {
#define SM_X(NAME, member) \
  if (name == #NAME) return static_cast<int64_t>(r.member);
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  uint64_t table = 0;  // SW_TABLE0/1: 16 two-bit codes a word
  for (int k = 31; k >= 0; --k) table = (table << 2) | (r.sw_table[static_cast<size_t>(k)] & 3u);
  if (name == "SW_TABLE0") return static_cast<int64_t>(table & 0xffffffffu);
  if (name == "SW_TABLE1") return static_cast<int64_t>(table >> 32);
  throw ToolError(fmt::format("{}: not a value register", name));
}

void set_register(const std::string& name, int64_t v, const HwConfig& hw, Regs& r, const std::string& what) {
  const auto setters = register_setters(r);
  const regmap::Reg* reg = find_register(name);
  const auto s = setters.find(name);
  if (!reg || s == setters.end()) throw ToolError(fmt::format("{}: not a value register", name));
  const Range rg = register_range(*reg, hw);
  if (v < rg.lo || v > rg.hi) throw ToolError(fmt::format("{} {} outside {}..{}", what, v, rg.lo, rg.hi));
  s->second(v);
}

RegsFile apply_regs_json(const std::string& path, HwConfig& hw, Regs& r) {
  std::ifstream in(path);
  if (!in) throw ToolError(fmt::format("{}: no such file", path));
  json j;
  try {
    in >> j;
  } catch (const json::exception&) {
    throw ToolError(fmt::format("{}: malformed JSON", path));
  }
  if (!j.is_object()) throw ToolError(fmt::format("{}: not a JSON object", path));

  auto integer = [&](const std::string& k, const json& v, int64_t lo, int64_t hi) {
    if (!v.is_number_integer())
      throw ToolError(fmt::format("{}: '{}' must be an integer {}..{}, not {}", path, k, lo, hi, v.dump()));
    const int64_t x = v.is_number_unsigned() ? static_cast<int64_t>(std::min<uint64_t>(v.get<uint64_t>(), INT64_MAX))
                                             : v.get<int64_t>();
    if (x < lo || x > hi) throw ToolError(fmt::format("{}: '{}' = {} is outside {}..{}", path, k, x, lo, hi));
    return x;
  };

  // Compile-time parameters first: the registers' ranges depend on them.
  // (the generated limits of rtl/defs.json; HwConfig::validate() checks parity and the rest)
  const std::map<std::string, int*> hw_fields = {{"MAX_WIDTH", &hw.max_width},
                                                 {"MAX_HEIGHT", &hw.max_height},
                                                 {"DISP", &hw.disp},
                                                 {"CENSUS", &hw.census},
                                                 {"SW", &hw.sw},
                                                 {"RECT_RADIUS", &hw.rect_radius},
                                                 {"COST_SHIFT", &hw.cost_shift},
                                                 {"MAX_OBJECTS", &hw.max_objects},
                                                 {"LABEL_SLOTS", &hw.label_slots},
                                                 {"BAND_K", &hw.band_k}};
  std::map<std::string, std::tuple<int64_t, int64_t, int*>> hw_keys;
  for (const auto& l : defs::kLimits) hw_keys[lower(l.name)] = {l.min, l.max, hw_fields.at(l.name)};
  RegsFile out;
  for (auto it = j.begin(); it != j.end(); ++it) {
    out.keys.push_back(it.key());
    if (auto h = hw_keys.find(it.key()); h != hw_keys.end()) {
      const auto& [lo, hi, field] = h->second;
      *field = static_cast<int>(integer(it.key(), it.value(), lo, hi));
    }
  }

  const auto setters = register_setters(r);
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const json& v = it.value();
    if (hw_keys.count(k)) continue;
    if (k == "sw_table") {
      if (!v.is_array() || v.empty() || v.size() > 32)
        throw ToolError(fmt::format("{}: 'sw_table' must be an array of 1..32 codes 0..3", path));
      r.sw_table.fill(0);
      for (size_t i = 0; i < v.size(); ++i)
        r.sw_table[i] = static_cast<uint8_t>(integer(fmt::format("sw_table[{}]", i), v[i], 0, 3));
      continue;
    }
    if (k == "calib") {
      if (!v.is_string() || v.get<std::string>().empty())
        throw ToolError(fmt::format("{}: 'calib' must be the path of a calibration file", path));
      fs::path p(v.get<std::string>());
      if (p.is_relative()) p = fs::path(path).parent_path() / p;
      out.calib = p.lexically_normal().string();
      continue;
    }
    const regmap::Reg* reg = nullptr;
    for (const auto& g : regmap::registers())
      if (lower(g.name) == k) reg = &g;
    const auto s = reg ? setters.find(reg->name) : setters.end();
    if (s == setters.end()) throw ToolError(fmt::format("{}: unknown key '{}'", path, k));
    const Range rg = register_range(*reg, hw);
    s->second(integer(k, v, rg.lo, rg.hi));
  }
  return out;
}

}  // namespace sm::tools
