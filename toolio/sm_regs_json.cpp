#include "sm_regs_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "sm_io.hpp"
#include "sm_json_file.hpp"
#include "sm_regmap.hpp"
#include "lower_case.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace sm::tools {

bool RegsFile::has(const std::string& key) const { return std::find(keys.begin(), keys.end(), key) != keys.end(); }

namespace {

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

using Set = void (*)(Regs&, int64_t);

// Setters of the run-time registers, by register name: every register whose fields are
// all rw and shadowed (the pipeline parameters), except CONTROL (not a parameter).
// Built once.
const std::map<std::string, Set>& register_setters() {
  static const std::map<std::string, Set> set = [] {
    std::map<std::string, Set> m{
        {"SW_TABLE0", [](Regs& r, int64_t v) { set_sw_table_word(r, 0, static_cast<uint32_t>(v)); }},
        {"SW_TABLE1", [](Regs& r, int64_t v) { set_sw_table_word(r, 1, static_cast<uint32_t>(v)); }}};
    // the value registers: the sm::Regs member of the register's name
#define SM_X(NAME, member) m[#NAME] = [](Regs& r, int64_t v) { r.member = static_cast<decltype(r.member)>(v); };
    SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
    return m;
  }();
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

bool is_value_register(const std::string& name) { return register_setters().count(name) != 0; }

// The one range check of register values, register-file keys and options:
// "<what> = <value> is outside <lo>..<hi>".
void check_range(const std::string& what, int64_t v, int64_t lo, int64_t hi) {
  if (v < lo || v > hi) throw ToolError(fmt::format("{} = {} is outside {}..{}", what, v, lo, hi));
}

}  // namespace

std::vector<ValueRegister> value_registers() {
  std::vector<ValueRegister> v;
  for (const auto& [name, set] : register_setters()) {
    (void)set;
    const regmap::Reg* reg = find_register(name);
    v.push_back({name, reg->desc, reg->addr});
  }
  std::sort(v.begin(), v.end(), [](const ValueRegister& a, const ValueRegister& b) { return a.addr < b.addr; });
  return v;
}

void set_config_resets_keeping(const RegsFile& f, const HwConfig& hw, Regs& r) {
  const Regs from_file = r;
  set_config_resets(hw, r);
  // a value register's file key is its sm::Regs member's name
#define SM_X(NAME, member) \
  if (f.has(#member)) r.member = from_file.member;
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
}

int64_t register_value(const std::string& name, const Regs& r) {
#define SM_X(NAME, member) \
  if (name == #NAME) return static_cast<int64_t>(r.member);
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  if (name == "SW_TABLE0") return sw_table_word(r, 0);
  if (name == "SW_TABLE1") return sw_table_word(r, 1);
  throw ToolError(fmt::format("{}: not a value register", name));
}

std::pair<int64_t, int64_t> register_limits(const std::string& name, const HwConfig& hw) {
  const regmap::Reg* reg = find_register(name);
  if (!reg) throw ToolError(fmt::format("{}: not a register", name));
  const Range rg = register_range(*reg, hw);
  return {rg.lo, rg.hi};
}

void set_register(const std::string& name, int64_t v, const HwConfig& hw, Regs& r, const std::string& what) {
  const auto& setters = register_setters();
  const regmap::Reg* reg = find_register(name);
  const auto s = setters.find(name);
  if (!reg || s == setters.end()) throw ToolError(fmt::format("{}: not a value register", name));
  const Range rg = register_range(*reg, hw);
  check_range(what, v, rg.lo, rg.hi);
  s->second(r, v);
}

RegsFile apply_regs_json(const std::string& path, HwConfig& hw, Regs& r) {
  json j;
  try {
    j = read_json_file(path);  // one value, no key twice
  } catch (const JsonFileError& e) {
    throw ToolError(e.what());
  }
  if (!j.is_object()) throw ToolError(fmt::format("{}: not a JSON object", path));

  auto what = [&](const std::string& k) { return fmt::format("{}: '{}'", path, k); };
  // An integer key's value; one above INT64_MAX is reported as written (outside lo..hi).
  auto integer = [&](const std::string& k, const json& v, Range rg) {
    if (!v.is_number_integer()) throw ToolError(fmt::format("{} must be an integer, not {}", what(k), v.dump()));
    if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX))
      throw ToolError(fmt::format("{} = {} is outside {}..{}", what(k), v.get<uint64_t>(), rg.lo, rg.hi));
    const int64_t x = v.is_number_unsigned() ? static_cast<int64_t>(v.get<uint64_t>()) : v.get<int64_t>();
    check_range(what(k), x, rg.lo, rg.hi);
    return x;
  };

  // Compile-time parameters first: the registers' ranges depend on them.
  // (the generated limits of rtl/defs.json; HwConfig::validate() checks parity and the rest)
  std::map<std::string, const defs::Limit*> hw_keys;
  for (const auto& l : defs::kLimits) hw_keys[lower_case(l.name)] = &l;
  RegsFile out;
  bool hw_set = false;
  for (auto it = j.begin(); it != j.end(); ++it) {
    out.keys.push_back(it.key());
    if (auto h = hw_keys.find(it.key()); h != hw_keys.end()) {
      const defs::Limit& l = *h->second;
      const int64_t x = integer(it.key(), it.value(), {l.min, l.max});
      *hw.field(l.name) = static_cast<int>(x);
      hw_set = true;
    }
  }
  // the file's configuration's resets (the file's registers below still win)
  if (hw_set) set_config_resets(hw, r);

  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const json& v = it.value();
    if (hw_keys.count(k)) continue;
    if (k == "sw_table") {
      if (!v.is_array() || v.empty() || v.size() > 32)
        throw ToolError(fmt::format("{}: 'sw_table' must be an array of 1..32 codes 0..3", path));
      r.sw_table.fill(0);
      for (size_t i = 0; i < v.size(); ++i) {
        const std::string ki = fmt::format("sw_table[{}]", i);
        const int64_t x = integer(ki, v[i], {0, 3});
        r.sw_table[i] = static_cast<uint8_t>(x);
      }
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
    // a register: its name in lower case
    const std::string name = upper(k);
    if (lower_case(name) != k || !is_value_register(name))
      throw ToolError(fmt::format("{}: unknown key '{}'", path, k));
    set_register(name, integer(k, v, register_range(*find_register(name), hw)), hw, r, what(k));
  }
  return out;
}

}  // namespace sm::tools
