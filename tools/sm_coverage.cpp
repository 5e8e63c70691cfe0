// sm_coverage: per-module line and toggle coverage of Verilator coverage data (the
// SystemC::Coverage-3 files that VerilatedCovContext::write and `verilator_coverage
// --write` produce), as a console table and as JSON (docs/verification.md, "Coverage").
//
// Every data line is `C '<key/value pairs>' <count>`, each pair \001<key>\002<value>.
// Verilator 5.006 names the kind of a point in its "page" key: v_line/<module> (a statement
// block or a case item), v_branch/<module> (the if and the else of an if) -- both come from
// --coverage-line -- and v_toggle/<module> (one bit of one signal, counted at every change;
// --coverage-toggle). The module is the RTL file of the point ("f", one module per file):
// the same point of every instance, parameter set and test (the same file, line, column,
// kind and comment, whatever the hierarchy "h" and the parameterized module name in
// "page") is one point, covered when one of them reached the threshold: a count >= 1 for a line
// point and >= 2 for a toggle point (two changes of one bit are a rise and a fall). The
// same key in several input files is summed first, as verilator_coverage --write does.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <filesystem>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "toolio/sm_cli.hpp"

namespace {

using json = nlohmann::ordered_json;

// One error line "sm_coverage: error: <msg>" and exit 1 (run_guarded in main).
[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

// The output files, all or nothing: each opened under a temporary name next to it before
// any work (a path that cannot be written, a folder or one of the inputs fails at once),
// renamed into place together by commit(); the temporaries are removed when the run fails.
class Outputs {
 public:
  explicit Outputs(const std::vector<std::string>& inputs) {
    for (const auto& in : inputs) inputs_.emplace_back(in, canonical(in));
  }
  Outputs(const Outputs&) = delete;
  Outputs& operator=(const Outputs&) = delete;
  ~Outputs() {
    for (auto& f : files_) std::remove(f.temp.c_str());
  }
  // The stream to write `path` to; `option` names it in the errors.
  std::ofstream& open(const std::string& option, const std::string& path) {
    for (const auto& f : files_)
      if (canonical(f.path) == canonical(path)) fail(fmt::format("{} {}: same file as {}", option, path, f.option));
    for (const auto& [in, abs] : inputs_)
      if (abs == canonical(path)) fail(fmt::format("{} {}: same file as the input {}", option, path, in));
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail(fmt::format("{} {}: cannot write: is a folder", option, path));
    const std::string temp = fmt::format("{}.tmp{}", path, ::getpid());
    files_.push_back({option, path, temp, std::make_unique<std::ofstream>(temp, std::ios::binary)});
    if (!*files_.back().out) fail(fmt::format("{} {}: cannot write: {}", option, path, std::strerror(errno)));
    return *files_.back().out;
  }
  void commit() {
    for (auto& f : files_) {
      f.out->close();
      if (!*f.out) fail(fmt::format("{} {}: write failed", f.option, f.path));
    }
    for (auto& f : files_)
      if (std::rename(f.temp.c_str(), f.path.c_str()) != 0)
        fail(fmt::format("{} {}: cannot write: {}", f.option, f.path, std::strerror(errno)));
    files_.clear();
  }

 private:
  static std::filesystem::path canonical(const std::string& p) {
    std::error_code ec;
    return std::filesystem::weakly_canonical(std::filesystem::absolute(p), ec);
  }
  struct File {
    std::string option, path, temp;
    std::unique_ptr<std::ofstream> out;
  };
  std::vector<File> files_;
  std::vector<std::pair<std::string, std::filesystem::path>> inputs_;
};

enum class Kind { kLine, kToggle, kOther };

struct Point {
  std::string file, line, column, page, comment, hier;
  Kind kind = Kind::kOther;
};

// Splits the key of one data line into its pairs; false when it is not well formed.
bool parse_key(const std::string& key, Point& p) {
  size_t i = 0;
  while (i < key.size()) {
    if (key[i] != '\001') return false;
    const size_t sep = key.find('\002', i + 1);
    if (sep == std::string::npos) return false;
    const size_t end = std::min(key.find('\001', sep + 1), key.size());
    const std::string k = key.substr(i + 1, sep - i - 1), v = key.substr(sep + 1, end - sep - 1);
    if (k == "f") {
      p.file = v;
    } else if (k == "l") {
      p.line = v;
    } else if (k == "n") {
      p.column = v;
    } else if (k == "page") {
      p.page = v;
    } else if (k == "o") {
      p.comment = v;
    } else if (k == "h") {
      p.hier = v;
    }
    i = end;
  }
  if (p.page.rfind("v_line/", 0) == 0 || p.page.rfind("v_branch/", 0) == 0) {
    p.kind = Kind::kLine;
  } else if (p.page.rfind("v_toggle/", 0) == 0) {
    p.kind = Kind::kToggle;
  }
  return !p.file.empty() && !p.page.empty();
}

std::string module_of(const std::string& file) {
  std::string b = file.substr(file.find_last_of('/') + 1);
  for (const char* ext : {".sv", ".v"}) {
    const std::string e = ext;
    if (b.size() > e.size() && b.compare(b.size() - e.size(), e.size(), e) == 0)
      return b.substr(0, b.size() - e.size());
  }
  return b;
}

// All data lines of the inputs, the counts of equal keys summed (key order kept).
struct Data {
  std::vector<std::string> keys;
  std::map<std::string, uint64_t> count;
};

void read_file(const std::string& path, Data& d) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(fmt::format("{}: cannot open", path));
  std::string s;
  if (!std::getline(in, s) || s.rfind("# SystemC::Coverage-", 0) != 0)
    fail(fmt::format("{}: not a Verilator coverage file (no '# SystemC::Coverage-' header)", path));
  int lineno = 1;
  while (std::getline(in, s)) {
    ++lineno;
    if (s.empty() || s[0] == '#') continue;
    const size_t q1 = s.find('\''), q2 = s.rfind('\'');
    if (s.rfind("C '", 0) != 0 || q2 <= q1) fail(fmt::format("{}:{}: not a coverage point", path, lineno));
    const std::string key = s.substr(q1 + 1, q2 - q1 - 1), num = s.substr(q2 + 1);
    const size_t b = num.find_first_not_of(" \t"), e = num.find_last_not_of(" \t\r");
    const std::string digits = b == std::string::npos ? std::string() : num.substr(b, e - b + 1);
    if (digits.empty() || digits.size() > 19 || digits.find_first_not_of("0123456789") != std::string::npos)
      fail(fmt::format("{}:{}: bad count '{}'", path, lineno, num));
    const uint64_t n = std::stoull(digits);
    Point p;
    if (!parse_key(key, p)) fail(fmt::format("{}:{}: point without file or page", path, lineno));
    auto [it, fresh] = d.count.emplace(key, 0);
    if (fresh) d.keys.push_back(key);
    it->second += n;
  }
}

struct Tally {
  uint64_t points = 0, covered = 0;
  std::optional<double> percent() const {
    if (points == 0) return std::nullopt;
    return std::round(10000.0 * static_cast<double>(covered) / static_cast<double>(points)) / 100.0;
  }
  json to_json() const {
    json j{{"points", points}, {"covered", covered}};
    const auto p = percent();
    j["percent"] = p ? json(*p) : json(nullptr);
    return j;
  }
};

// Uncovered points of one module, by source line: a line or branch point on its own (its
// column and comment), a signal's toggle points together (how many of its bits).
struct Missed {
  uint64_t points = 0, missed = 0, best = 0;  // best: highest count of a missed point
};
struct Module {
  std::string file;
  Tally line, toggle;
  std::map<std::pair<unsigned long, std::string>, Missed> missed;
};

std::string pct(const Tally& t) {
  const auto p = t.percent();
  return p ? fmt::format("{:.1f}", *p) : std::string("-");
}

void write_subset(std::ostream& out, const Data& d, Kind kind) {
  out << "# SystemC::Coverage-3\n";
  for (const auto& k : d.keys) {
    Point p;
    parse_key(k, p);
    if (p.kind == kind) out << "C '" << k << "' " << d.count.at(k) << "\n";
  }
}

int run(int argc, char** argv) {
  CLI::App app{"Per-module line and toggle coverage of Verilator coverage data"};
  std::vector<std::string> inputs;
  std::string json_path, line_dat, toggle_dat;
  uint64_t line_min = 1, toggle_min = 2;
  double goal_line = 95.0, goal_toggle = 85.0;
  bool markdown = false, list = false;
  app.add_option("inputs", inputs, "coverage data files (.dat); equal points are summed")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--json", json_path, "write the per-module table as JSON");
  app.add_option("--line-dat", line_dat, "write the line and branch points (summed) to this .dat");
  app.add_option("--toggle-dat", toggle_dat, "write the toggle points (summed) to this .dat");
  app.add_option("--line-min", line_min, "count at which a line or branch point is covered")
      ->capture_default_str()
      ->check(sm::tools::int_in(1, INT64_MAX));
  app.add_option("--toggle-min", toggle_min, "count at which a toggle point (one bit) is covered")
      ->capture_default_str()
      ->check(sm::tools::int_in(1, INT64_MAX));
  app.add_option("--goal-line", goal_line, "line goal in percent")
      ->capture_default_str()
      ->check(sm::tools::finite_in(0, 100));
  app.add_option("--goal-toggle", goal_toggle, "toggle goal in percent")
      ->capture_default_str()
      ->check(sm::tools::finite_in(0, 100));
  app.add_flag("--markdown", markdown, "print the table as markdown");
  app.add_flag("--list-uncovered", list, "list the uncovered points of the modules below a goal");
  if (const auto rc = sm::tools::parse_cli(app, argc, argv)) return *rc;
  Outputs outs(inputs);
  std::ofstream* json_out = json_path.empty() ? nullptr : &outs.open("--json", json_path);
  std::ofstream* line_out = line_dat.empty() ? nullptr : &outs.open("--line-dat", line_dat);
  std::ofstream* toggle_out = toggle_dat.empty() ? nullptr : &outs.open("--toggle-dat", toggle_dat);

  Data d;
  for (const auto& f : inputs) read_file(f, d);
  if (d.keys.empty()) fail("no coverage points in the input");

  // Same point of every instance: the key without its hierarchy; the best count wins.
  struct Best {
    Point p;
    uint64_t count = 0;
  };
  std::map<std::string, Best> points;
  uint64_t other = 0;
  for (const auto& k : d.keys) {
    Point p;
    parse_key(k, p);
    if (p.kind == Kind::kOther) {
      ++other;
      continue;
    }
    // the page names the module as Verilator parameterized it (v_line/sm_x__W8...): one
    // point of the file for every parameter set
    const std::string id =
        p.file + '\n' + p.line + '\n' + p.column + '\n' + p.page.substr(0, p.page.find('/')) + '\n' + p.comment;
    auto [it, fresh] = points.emplace(id, Best{p, 0});
    it->second.count = std::max(it->second.count, d.count.at(k));
  }

  std::map<std::string, Module> mods;
  for (const auto& [id, b] : points) {
    Module& m = mods[module_of(b.p.file)];
    if (m.file.empty()) {
      m.file = b.p.file;
    } else if (m.file != b.p.file) {
      fail(fmt::format("module {} is in two files: {} and {}", module_of(b.p.file), m.file, b.p.file));
    }
    const bool line = b.p.kind == Kind::kLine;
    Tally& t = line ? m.line : m.toggle;
    ++t.points;
    const bool hit = b.count >= (line ? line_min : toggle_min);
    if (hit) ++t.covered;
    const std::string what =
        line ? fmt::format("{} {} (column {})", b.p.page.substr(0, b.p.page.find('/')), b.p.comment, b.p.column)
             : fmt::format("toggle {}", b.p.comment.substr(0, b.p.comment.find('[')));
    Missed& x = m.missed[{std::strtoul(b.p.line.c_str(), nullptr, 10), what}];
    ++x.points;
    if (!hit) {
      ++x.missed;
      x.best = std::max(x.best, b.count);
    }
  }

  Tally tl, tt;
  auto below = [&](const Module& m) {
    const auto l = m.line.percent(), t = m.toggle.percent();
    return (l && *l < goal_line) || (t && *t < goal_toggle);
  };
  if (markdown) {
    fmt::print("| module | line points | line % | toggle points | toggle % | below goal |\n");
    fmt::print("|---|---:|---:|---:|---:|---|\n");
  } else {
    fmt::print("{:<22} {:>13} {:>7} {:>15} {:>8}\n", "module", "line", "line %", "toggle", "toggle %");
  }
  for (const auto& [name, m] : mods) {
    tl.points += m.line.points;
    tl.covered += m.line.covered;
    tt.points += m.toggle.points;
    tt.covered += m.toggle.covered;
    const std::string lc = fmt::format("{}/{}", m.line.covered, m.line.points);
    const std::string tc = fmt::format("{}/{}", m.toggle.covered, m.toggle.points);
    if (markdown) {
      fmt::print("| `{}` | {} | {} | {} | {} | {} |\n", name, lc, pct(m.line), tc, pct(m.toggle),
                 below(m) ? "yes" : "");
    } else {
      fmt::print("{:<22} {:>13} {:>7} {:>15} {:>8}{}\n", name, lc, pct(m.line), tc, pct(m.toggle),
                 below(m) ? "  below goal" : "");
    }
  }
  const std::string lc = fmt::format("{}/{}", tl.covered, tl.points), tc = fmt::format("{}/{}", tt.covered, tt.points);
  if (markdown) {
    fmt::print("| all | {} | {} | {} | {} | |\n", lc, pct(tl), tc, pct(tt));
  } else {
    fmt::print("{:<22} {:>13} {:>7} {:>15} {:>8}\n", "all", lc, pct(tl), tc, pct(tt));
    fmt::print("goal: line {} %, toggle {} %; covered at count >= {} (line), >= {} (toggle){}\n", goal_line,
               goal_toggle, line_min, toggle_min,
               other ? fmt::format("; points of other kinds (ignored): {}", other) : std::string());
  }
  if (list)
    for (const auto& [name, m] : mods)
      if (below(m)) {
        fmt::print("\n{} ({}): uncovered line {}, toggle {}\n", name, m.file, m.line.points - m.line.covered,
                   m.toggle.points - m.toggle.covered);
        for (const auto& [where, x] : m.missed) {
          if (x.missed == 0) continue;
          if (x.points > 1) {
            fmt::print("  {}: {}: {} of {} bits (highest count {})\n", where.first, where.second, x.missed, x.points,
                       x.best);
          } else {
            fmt::print("  {}: {} (count {})\n", where.first, where.second, x.best);
          }
        }
      }

  if (!json_path.empty()) {
    json j;
    j["tool"] = "sm_coverage";
    j["inputs"] = inputs;
    j["line_min"] = line_min;
    j["toggle_min"] = toggle_min;
    j["goal"] = {{"line", goal_line}, {"toggle", goal_toggle}};
    j["ignored_points"] = other;
    j["modules"] = json::object();
    for (const auto& [name, m] : mods)
      j["modules"][name] = {
          {"file", m.file}, {"line", m.line.to_json()}, {"toggle", m.toggle.to_json()}, {"below_goal", below(m)}};
    j["total"] = {{"line", tl.to_json()}, {"toggle", tt.to_json()}};
    *json_out << j.dump(2) << "\n";
  }
  if (line_out) write_subset(*line_out, d, Kind::kLine);
  if (toggle_out) write_subset(*toggle_out, d, Kind::kToggle);
  outs.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return sm::tools::run_guarded("sm_coverage", [&] { return run(argc, argv); });
}
