// The legal range (and parity) of an sm_top parameter as a CLI11 check, from rtl/defs.json's
// limits (the generated sm_defs.hpp): an option that sets a parameter out of its range fails
// the parse (exit 2, "--disp: 0: must be even, 4..254") like every other option's range,
// instead of the hardware configuration's check after the parse. Combinations of parameters
// stay HwConfig::validate()'s. Header-only beside sm_cli.hpp, which cannot include the
// generated header (sm_regmap_gen, which writes it, uses sm_cli.hpp).
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "sm_cli.hpp"
#include "sm_defs.hpp"

namespace sm::tools {

inline CLI::Validator param_in(const char* name) {
  using sm::defs::Parity;
  const sm::defs::Limit& l = sm::defs::limit(name);
  const char* kind = l.parity == Parity::kEven ? "even, " : l.parity == Parity::kOdd ? "odd, " : "";
  const std::string range = fmt::format("{}{}..{}", kind, l.min, l.max);
  return CLI::Validator(
      [l, range](std::string& s) -> std::string {
        int64_t v = 0;
        const bool ok = detail::to_int64(s, v) && v >= l.min && v <= l.max &&
                        (l.parity == Parity::kAny || (v % 2 == 0) == (l.parity == Parity::kEven));
        return ok ? std::string() : fmt::format("{}: must be {}", s, range);
      },
      fmt::format("INT in {}..{}{}", l.min, l.max,
                  l.parity == Parity::kEven  ? ", even"
                  : l.parity == Parity::kOdd ? ", odd"
                                             : ""));
}

}  // namespace sm::tools
