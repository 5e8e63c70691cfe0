// Waves a debugging engineer can use (issue 22), on the small configuration: stereo_sim's
// --wave-scope / --wave-depth dump one block's signals and no other block's, in VCD and in
// FST (the same signals), an unknown scope is one error line and leaves no wave file, the
// plain (depth-1) simulator refuses a block scope, and every GTKWave save file of
// waves/gtkw names signals of a dump of its own scope (the exact names, bit ranges
// included, at the paper configuration when stereo_sim_wave is built: SM_WAVE_PAPER).

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sm_cmd.hpp"
#include "sm_wave_names.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kTmp = fs::path(SM_TEST_TMP);

sm::test::CmdResult run(const std::string& exe, const std::string& args) {
  fs::create_directories(kTmp);
  return sm::test::run_cmd(exe, args + " -q --frames 1 --out \"" + (kTmp / "out").string() + "\"", kTmp);
}

// A dump of `scopes` at `depth` (2 lines of the small scene from line 4) by `exe`.
std::vector<std::string> dump(const std::string& exe, const fs::path& file, const std::vector<std::string>& scopes,
                              int depth) {
  std::string args = fmt::format("--wave \"{}\" --vcd-line 4 --vcd-lines 2", file.string());
  for (const auto& s : scopes) args += " --wave-scope " + s;
  if (!scopes.empty()) args += fmt::format(" --wave-depth {}", depth);
  const sm::test::CmdResult r = run(exe, args);
  INFO(r.out << r.err);
  REQUIRE(r.rc == 0);
  REQUIRE(fs::exists(file));
  if (sm::wave_extension(file.string()) == "vcd") return sm::vcd_signal_names(file.string());
  // FST: read back by stereo_sim's own --wave-list (the FST reader is in the wave build).
  const sm::test::CmdResult l = sm::test::run_cmd(exe, "--wave-list \"" + file.string() + "\"", kTmp);
  REQUIRE(l.rc == 0);
  std::vector<std::string> names;
  std::istringstream in(l.out);
  for (std::string s; std::getline(in, s);)
    if (!s.empty()) names.push_back(s);
  return names;
}

size_t count_prefix(const std::vector<std::string>& names, const std::string& scope) {
  return static_cast<size_t>(
      std::count_if(names.begin(), names.end(), [&](const std::string& n) { return n.rfind(scope + ".", 0) == 0; }));
}

// Levels of `name` below `scope` (1: a signal of the scope itself).
int level_below(const std::string& name, const std::string& scope) {
  const std::string rest = name.substr(scope.size() + 1);
  const std::string base = rest.substr(0, rest.find('['));  // a range may hold no '.', but stay safe
  return 1 + static_cast<int>(std::count(base.begin(), base.end(), '.'));
}

std::string strip_range(const std::string& n) {
  const size_t b = n.rfind('[');
  return b != std::string::npos && n.back() == ']' ? n.substr(0, b) : n;
}

// Identifiers with value changes in a VCD that its header never declared.
size_t undeclared_ids(const fs::path& p) {
  std::ifstream in(p);
  std::set<std::string> ids;
  std::string tok;
  while (in >> tok && tok != "$enddefinitions")
    if (tok == "$var") {
      std::string type, width, id;
      in >> type >> width >> id;
      ids.insert(id);
    }
  size_t bad = 0;
  for (std::string l; in >> l;) {  // value changes have no blank inside but "b0101 id"
    if (l[0] == '#' || l[0] == '$') continue;
    if (l[0] == 'b' || l[0] == 'r') {
      std::string id;
      in >> id;
      bad += ids.count(id) == 0;
      continue;
    }
    bad += ids.count(l.substr(1)) == 0;
  }
  return bad;
}

struct Gtkw {
  fs::path path;
  std::vector<std::string> scopes;
  int depth = 0;
  std::vector<std::string> signals;
};

// The scopes and depth a save file is for ("[*] scope: ..." and "[*] depth: ..." comment
// lines) and the signals it shows (every line that is not a directive, flag or comment).
Gtkw read_gtkw(const fs::path& p) {
  Gtkw g;
  g.path = p;
  std::ifstream in(p);
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("[*] scope: ", 0) == 0) {
      g.scopes.push_back(l.substr(11));
    } else if (l.rfind("[*] depth: ", 0) == 0) {
      g.depth = std::stoi(l.substr(11));
    } else if (!l.empty() && l[0] != '[' && l[0] != '@' && l[0] != '-' && l[0] != '*') {
      g.signals.push_back(l);
    }
  }
  return g;
}

std::vector<Gtkw> save_files() {
  std::vector<Gtkw> v;
  for (const auto& e : fs::directory_iterator(SM_GTKW_DIR))
    if (e.path().extension() == ".gtkw") v.push_back(read_gtkw(e.path()));
  std::sort(v.begin(), v.end(), [](const Gtkw& a, const Gtkw& b) { return a.path < b.path; });
  return v;
}

}  // namespace

TEST_CASE("a block scope dumps that block's signals and no other block's, VCD and FST alike") {
  const std::string dp = "TOP.sm_top.u_dp", census = "TOP.sm_top.u_census";
  const auto d1 = dump(SM_STEREO_SIM_SMALL_WAVE, kTmp / "dp1.vcd", {dp}, 1);
  REQUIRE(!d1.empty());
  CHECK(count_prefix(d1, dp) == d1.size());  // nothing outside the DP: not sm_top's own wires
  CHECK(count_prefix(d1, census) == 0);
  for (const auto& n : d1) CHECK(level_below(n, dp) == 1);
  for (const char* s : {"TOP.sm_top.u_dp.clk", "TOP.sm_top.u_dp.ce"})
    CHECK(std::find(d1.begin(), d1.end(), s) != d1.end());
  // Depth 2 adds the DP's children (its processing elements, the traceback), no deeper.
  const auto d2 = dump(SM_STEREO_SIM_SMALL_WAVE, kTmp / "dp2.vcd", {dp}, 2);
  CHECK(count_prefix(d2, dp) == d2.size());
  CHECK(d2.size() > d1.size());
  int deepest = 0;
  for (const auto& n : d2) deepest = std::max(deepest, level_below(n, dp));
  CHECK(deepest == 2);
  // Depth 0: every level below the DP; a second scope adds the census and nothing else.
  const auto dall = dump(SM_STEREO_SIM_SMALL_WAVE, kTmp / "dpall.vcd", {dp, "u_census"}, 0);
  CHECK(count_prefix(dall, dp) + count_prefix(dall, census) == dall.size());
  CHECK(count_prefix(dall, dp) > d2.size());
  CHECK(count_prefix(dall, census) > 0);
  CHECK(undeclared_ids(kTmp / "dp1.vcd") == 0);
  CHECK(undeclared_ids(kTmp / "dp2.vcd") == 0);
  // FST: the same signals as the VCD of the same scope.
  const auto f2 = dump(SM_STEREO_SIM_SMALL_WAVE, kTmp / "dp2.fst", {dp}, 2);
  CHECK(std::set<std::string>(f2.begin(), f2.end()) == std::set<std::string>(d2.begin(), d2.end()));
  CHECK(sm::test::slurp(kTmp / "dp2.fst").size() < sm::test::slurp(kTmp / "dp2.vcd").size());
}

// A narrow selection: Verilator's trace runtime enables codes at random past the last
// selected one unless the wave build's fixed copy is in (sim/sim.cmake); the FST writer
// then crashes, the VCD writer writes values of undeclared identifiers.
TEST_CASE("one signal as the scope: that signal alone, VCD and FST") {
  for (const char* ext : {"vcd", "fst"}) {
    INFO(ext);
    const auto n = dump(SM_STEREO_SIM_SMALL_WAVE, kTmp / fmt::format("ce.{}", ext), {"TOP.sm_top.ce"}, 1);
    CHECK(n == std::vector<std::string>{"TOP.sm_top.ce"});
  }
  CHECK(undeclared_ids(kTmp / "ce.vcd") == 0);
}

TEST_CASE("an unknown scope is one error line and leaves no wave file") {
  const fs::path f = kTmp / "bad.fst";
  fs::create_directories(kTmp);
  { std::ofstream(f) << "stale"; }  // an earlier run's file must not look like this run's
  const auto r = run(SM_STEREO_SIM_SMALL_WAVE, fmt::format("--wave \"{}\" --wave-scope TOP.sm_top.u_nope", f.string()));
  CHECK(r.rc != 0);
  CHECK(r.err.find("u_nope") != std::string::npos);
  // one error line (besides the note that the default scene was resized, shown with -q too)
  const std::string note = "note: input resized to the active size 64x48\n";
  const std::string err = r.err.rfind(note, 0) == 0 ? r.err.substr(note.size()) : r.err;
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK(!fs::exists(f));
  CHECK(!fs::exists(kTmp / "bad.part.fst"));
  // A prefix of a real name is not a scope (u_d is not u_dp).
  CHECK(run(SM_STEREO_SIM_SMALL_WAVE, fmt::format("--wave \"{}\" --wave-scope u_d", f.string())).rc != 0);
  // Neither a format other than .vcd / .fst, nor a block scope in the plain simulator
  // (trace depth 1: sm_top's own signals), nor FST there.
  CHECK(run(SM_STEREO_SIM_SMALL_WAVE, "--wave " + (kTmp / "x.lxt").string()).rc != 0);
  const auto p = run(SM_STEREO_SIM_SMALL, "--wave " + (kTmp / "p.vcd").string() + " --wave-scope u_dp");
  CHECK(p.rc != 0);
  CHECK(p.err.find("stereo_sim_wave") != std::string::npos);
  CHECK(!fs::exists(kTmp / "p.vcd"));
  CHECK(run(SM_STEREO_SIM_SMALL, "--wave " + (kTmp / "p.fst").string()).rc != 0);
  // ... while its unscoped VCD window (sm_top's own signals) stays as it was.
  const auto top = dump(SM_STEREO_SIM_SMALL, kTmp / "top.vcd", {}, 0);
  CHECK(count_prefix(top, "TOP.sm_top") > 0);
  CHECK(count_prefix(top, "TOP.sm_top.u_dp") == 0);
  CHECK(std::find(top.begin(), top.end(), "TOP.sm_top.dp_disp[15:0]") != top.end());
}

TEST_CASE("every GTKWave save file shows signals of a dump of its own scope") {
  const auto files = save_files();
  REQUIRE(files.size() >= 7);
  std::set<std::string> seen_scopes;
  for (const Gtkw& g : files) {
    INFO(g.path.string());
    REQUIRE(!g.scopes.empty());
    REQUIRE(!g.signals.empty());
    for (const auto& s : g.scopes) seen_scopes.insert(s);
    // Small configuration: the names without their bit ranges (those differ from the
    // paper configuration's, which the save files are written for).
    const auto names = dump(SM_STEREO_SIM_SMALL_WAVE, kTmp / (g.path.stem().string() + ".vcd"), g.scopes, g.depth);
    std::set<std::string> bases;
    for (const auto& n : names) bases.insert(strip_range(n));
    for (const auto& s : g.signals) {
      INFO(s);
      CHECK(bases.count(strip_range(s)) == 1);
    }
#ifdef SM_STEREO_SIM_WAVE
    // Paper configuration: the exact names GTKWave looks up.
    const auto paper = dump(SM_STEREO_SIM_WAVE, kTmp / (g.path.stem().string() + "_paper.fst"), g.scopes, g.depth);
    const std::set<std::string> exact(paper.begin(), paper.end());
    for (const auto& s : g.signals) {
      INFO(s);
      CHECK(exact.count(s) == 1);
    }
#endif
  }
  // One per major block.
  for (const char* s : {"TOP.sm_top.u_bright", "TOP.sm_top.u_census", "TOP.sm_top.u_agg", "TOP.sm_top.u_dp",
                        "TOP.sm_top.u_post1", "TOP.sm_top.u_objects", "TOP.sm_top.u_regs"})
    CHECK(seen_scopes.count(s) == 1);
}
