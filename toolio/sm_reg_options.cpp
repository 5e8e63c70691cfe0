#include "sm_reg_options.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "sm_regs_json.hpp"
#include "lower_case.hpp"

namespace sm::tools {

namespace {

std::string option_name(const std::string& reg) {
  std::string o = "--" + lower_case(reg);
  std::replace(o.begin(), o.end(), '_', '-');
  return o;
}

}  // namespace

RegOptions::RegOptions(CLI::App& app, const Regs& defaults, const HwConfig& hw, const std::set<std::string>& skip,
                       const std::map<std::string, std::string>& aliases) {
  for (const auto& v : value_registers()) {
    if (skip.count(v.name) || v.name == "SW_TABLE0" || v.name == "SW_TABLE1") continue;
    auto o = std::make_unique<Opt>();
    o->reg = v.name;
    std::string names = option_name(v.name);
    if (const auto a = aliases.find(v.name); a != aliases.end()) names += "," + a->second;
    const auto [lo, hi] = register_limits(v.name, hw);
    // the range shown as int_in shows it; the check is apply()'s (the configuration may
    // still change with other options)
    const CLI::Validator range([](std::string&) { return std::string(); }, fmt::format("INT in {}..{}", lo, hi));
    o->opt = app.add_option(names, o->value, fmt::format("{} (register {})", v.desc, v.name))
                 ->check(range)
                 ->default_str(std::to_string(register_value(v.name, defaults)));
    opts_.push_back(std::move(o));
  }
}

void RegOptions::apply(const HwConfig& hw, Regs& r) const {
  for (const auto& o : opts_)
    if (o->opt->count()) set_register(o->reg, o->value, hw, r, option_name(o->reg));
}

}  // namespace sm::tools
