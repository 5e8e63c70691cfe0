// Command lines of the tools: the exit codes, the one-line error of a CLI11 parse error,
// the guard around a tool's main() and option validators that name the option and the
// reason (finite numbers in a range, integers in a range, unsigned integers). Header-only
// (CLI11 and fmt only) so that the tools built before sm_toolio (sm_regmap_gen) and those
// that do not link it (sm_synth_report, sm_coverage) share it. docs/robustness.md.
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

namespace sm::tools {

// Exit codes of every tool (README, docs/robustness.md): 0 done (and --help), 1 an error
// in an input, an output or a value the tool checked, 2 a command line CLI11 could not
// parse (unknown option, missing or malformed value, a validator below failed).
constexpr int kExitError = 1;
constexpr int kExitUsage = 2;

// A command-line error: run_guarded() prints it like any error and exits kExitUsage.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

namespace detail {

// The value given to `o` at argv[i] ("--name value", "--name=value", "-n value"), if any.
inline std::optional<std::string> option_value(const CLI::Option& o, int argc, char** argv, int i) {
  const std::string a = argv[i];
  for (const std::string& n : o.get_lnames()) {
    if (a == "--" + n && i + 1 < argc) return std::string(argv[i + 1]);
    if (a.rfind("--" + n + "=", 0) == 0) return a.substr(n.size() + 3);
  }
  for (const std::string& n : o.get_snames())
    if (a == "-" + n && i + 1 < argc) return std::string(argv[i + 1]);
  return std::nullopt;
}

}  // namespace detail

// CLI11 drops the empty items of a delimited value ("a,,b" gives a and b): a value of a
// delimited option with an empty item (doubled, leading or trailing delimiter, or none at
// all) is refused instead, naming the option, so a typo never runs on a shorter list.
inline void check_delimited(const CLI::App& app, int argc, char** argv) {
  for (const CLI::Option* o : app.get_options()) {
    const char d = o->get_delimiter();
    if (d == '\0') continue;
    for (int i = 1; i < argc && std::string(argv[i]) != "--"; ++i) {
      const std::optional<std::string> v = detail::option_value(*o, argc, argv, i);
      if (!v) continue;
      const std::string s = std::string(1, d) + *v + std::string(1, d);
      if (s.find(std::string(2, d)) != std::string::npos)
        throw UsageError(fmt::format("{}: '{}': an empty item in a '{}'-separated list", o->get_name(), *v, d));
    }
  }
}

// Parses argv into app. --help (and --help-all): printed by CLI11, returns 0 (the tool
// stops). Any other parse error, or an empty item of a delimited value: throws UsageError
// with a one-line message.
inline std::optional<int> parse_cli(CLI::App& app, int argc, char** argv) {
  check_delimited(app, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    if (const size_t nl = msg.find('\n'); nl != std::string::npos) msg = msg.substr(0, nl);
    throw UsageError(msg);
  }
  return std::nullopt;
}

// Runs `body` and turns an exception into the one line "<tool>: error: <what>" on stderr:
// exit kExitUsage for a UsageError, kExitError for any other.
template <class F>
int run_guarded(const char* tool, F&& body) {
  try {
    return body();
  } catch (const UsageError& e) {
    fmt::print(stderr, "{}: error: {}\n", tool, e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: error: {}\n", tool, e.what());
    return kExitError;
  }
}

namespace detail {

// The whole string as a double (strtod: also "nan", "inf"); false when anything is left.
inline bool to_double(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

// The whole string as a signed 64-bit integer (decimal); false when anything is left or
// it overflows.
inline bool to_int64(const std::string& s, int64_t& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtoll(s.c_str(), &end, 10);
  return end == s.c_str() + s.size() && errno != ERANGE;
}

}  // namespace detail

// A finite number in lo..hi (CLI11 prefixes the option's name): "nan: not a finite
// number", "7: outside 0..5".
inline CLI::Validator finite_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        double v = 0;
        if (!detail::to_double(s, v)) return fmt::format("'{}': not a number", s);
        if (!std::isfinite(v)) return fmt::format("{}: not a finite number", s);
        if (v < lo || v > hi) return fmt::format("{}: outside {}..{}", s, lo, hi);
        return {};
      },
      fmt::format("FLOAT in {}..{}", lo, hi));
}

// Any finite number.
inline CLI::Validator finite() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double v = 0;
        if (!detail::to_double(s, v)) return fmt::format("'{}': not a number", s);
        if (!std::isfinite(v)) return fmt::format("{}: not a finite number", s);
        return {};
      },
      "FINITE");
}

// A decimal integer in lo..hi: "abc: not an integer", "0: outside 1..1000".
inline CLI::Validator int_in(int64_t lo, int64_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        int64_t v = 0;
        if (!detail::to_int64(s, v)) return fmt::format("'{}': not an integer in {}..{}", s, lo, hi);
        if (v < lo || v > hi) return fmt::format("{}: outside {}..{}", s, lo, hi);
        return {};
      },
      fmt::format("INT in {}..{}", lo, hi));
}

}  // namespace sm::tools
