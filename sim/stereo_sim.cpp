// stereo_sim: cycle-accurate simulation of the stereo IP (Verilated sm_top). This file is
// the part compiled once per configuration: the Verilated model's run. The program
// itself (command line, inputs, check against the reference model, report) is
// stereo_sim_app.cpp and its stages, compiled once (stereo_sim_app.hpp says why).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include "sm_coverage.hpp"
#include "sm_regmap.hpp"
#include "sm_regs_io.hpp"
#include "sm_sim.hpp"
#include "sm_sim_interrupt.hpp"
#include "sm_sim_progress.hpp"
#include "sm_vconfig.hpp"
#include "sm_wave_names.hpp"
#include "stereo_sim_app.hpp"
#include "toolio/sm_signal_cleanup.hpp"
#if SM_WAVE_BUILD
#ifdef SM_WAVE_VCD
#include SM_WAVE_VCD_H
#endif
#ifdef SM_WAVE_FST
#include SM_WAVE_FST_H
#endif
#else
#include SM_VTOP_H
#endif

namespace fs = std::filesystem;

namespace {

using sm::simapp::RunRequest;
using sm::simapp::RunResult;

[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

// What this executable traces.
#if SM_WAVE_BUILD
constexpr const char* kTraced = "every signal of sm_top, at every depth";
#else
constexpr const char* kTraced =
    "sm_top's own signals only (trace depth 1); the blocks' internals and FST are in stereo_sim_wave / "
    "stereo_sim_small_wave";
#endif

// Whether a signal name (GTKWave's, '.'-separated) is inside `scope`: below it, or the
// scope is the signal itself (dumpvars takes a signal's path too).
bool in_scope(const std::string& name, const std::string& scope) {
  if (name.rfind(scope, 0) != 0) return false;
  const std::string rest = name.substr(scope.size());
  return rest.empty() || rest[0] == '.' || (rest[0] == '[' && rest.find('.') == std::string::npos);
}

// Each scope must hold at least one traced signal: a trace of it alone is written and
// read back before the run (no clock moves), and --wave-scopes lists them all. Returns
// false when it only listed them.
template <class Top>
bool probe_scopes(sm::Testbench<Top>& tb, const RunRequest& req) {
  const std::string& wave_path = req.window.path;
  const fs::path dir = wave_path.empty() ? fs::temp_directory_path() : fs::path(wave_path).parent_path();
  if (!dir.empty()) fs::create_directories(dir);
  const std::string probe =
      ((dir.empty() ? fs::path(".") : dir) / fmt::format(".stereo_sim_probe_{}.{}", ::getpid(), req.wave_fmt)).string();
  sm::simapp::PartFile probe_guard{probe, "", false};
  const sm::tools::RemoveOnSignal probe_on_signal(probe);
  // The top level's own signals (its ports) are always in the probe.
  auto names_of = [&](sm::TraceScope sel) {
    if (!sel.scopes.empty()) sel.scopes.push_back({"TOP", 1});
    if (!tb.probe_trace(probe, sel)) fail("this simulator was built without tracing");
    return sm::wave_signal_names(probe);
  };
  if (req.list_scopes) {
    std::vector<std::string> scopes;
    for (const auto& n : names_of({})) {
      for (size_t p = n.find('.'); p != std::string::npos; p = n.find('.', p + 1)) scopes.push_back(n.substr(0, p));
    }
    std::sort(scopes.begin(), scopes.end());
    scopes.erase(std::unique(scopes.begin(), scopes.end()), scopes.end());
    for (const auto& sc : scopes) fmt::print("{}\n", sc);
    return false;
  }
  for (const auto& sc : req.wave_scopes) {
    const auto names = names_of({{{sc, req.wave_depth}}});
    if (std::none_of(names.begin(), names.end(), [&](const std::string& n) { return in_scope(n, sc); }))
      fail(
          fmt::format("--wave-scope {}: no traced signal in this scope (this simulator traces {}; "
                      "--wave-scopes lists its scopes)",
                      sc, kTraced));
  }
  return true;
}

// The wave window is written as <stem>.part.<ext>, renamed when it is complete.
void start_wave_part(const std::string& wave_path, sm::simapp::PartFile& part) {
  const fs::path p(wave_path);
  fs::create_directories(p.parent_path().empty() ? fs::path(".") : p.parent_path());
  part.final_path = wave_path;
  part.path = (p.parent_path() / (p.stem().string() + ".part" + p.extension().string())).string();
  std::error_code ec;
  fs::remove(part.path, ec);
}

// What the host reads back at the end: STATUS and the error registers.
template <class Top>
void read_status(sm::SimEngine<Top>& sim, RunResult& out) {
  const auto& regs = sm::regmap::registers();
  for (size_t i = 0; i < regs.size(); ++i) {
    const std::string name = regs[i].name;
    if (name != "STATUS" && name != "IN_FIFO" && name.rfind("ERR_", 0) != 0) continue;
    unsigned resp = 0;
    const uint32_t word = sim.axil().read(regs[i].addr, &resp);
    if (resp != 0) fail(fmt::format("status read of {} refused", name));
    out.status.emplace_back(i, word);
  }
}

template <class Top>
bool run_model(const RunRequest& req, RunResult& out) {
  if (!req.quiet) sm::simapp::end_progress_line_on_signal();  // before any RemoveOnSignal
  sm::Testbench<Top> tb;
  sm::CoverageOnExit cov{tb->contextp()};  // the coverage build's data (SM_COVERAGE_FILE)
  const std::string& wave_path = req.window.path;
  if ((req.list_scopes || !req.wave_scopes.empty()) && !probe_scopes(tb, req)) return false;
  sm::SimEngine<Top> sim(tb);
  sim.reset();
  sm::write_registers(sim.axil(), *req.regs0, sm::verilated_config());
  sm::VcdWindow vw = req.window;
  sm::simapp::PartFile part;
  sm::tools::RemoveOnSignal part_on_signal;  // Ctrl-C leaves no half-written window
  if (!wave_path.empty()) {
    start_wave_part(wave_path, part);
    part_on_signal = sm::tools::RemoveOnSignal(part.path);
    vw.path = part.path;
  }
  // the wave's time stamps in the core clock's real period (ps)
  tb.set_clock_period_ps(static_cast<uint64_t>(std::llround(1e12 / req.timing.aclk_hz(req.width, req.height))));
  const auto t0 = std::chrono::steady_clock::now();
  sm::simapp::SimProgress progress(req.feed.count, req.height, req.quiet);
  sim.on_row = [&](size_t frame, int row) { progress.row(frame, row); };
  sim.on_frame = [&](size_t done, size_t total) { progress.frame(done, total); };
  out.res = sim.run(req.feed, req.width, req.height, req.timing, vw, 0, req.host);
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  tb.close_trace();
  if (!part.path.empty()) {
    if (!fs::exists(part.path)) fail(fmt::format("--wave {}: the window never opened", wave_path));
    fs::rename(part.path, part.final_path);
    part.done = true;
  }
  read_status(sim, out);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  sm::simapp::ModelInfo info;
  info.hw = sm::verilated_config();
  info.traced = kTraced;
  info.default_scene = SM_DEFAULT_SCENE;
  info.synth_json = SM_SYNTH_JSON;
  info.synth_json_docs = SM_SYNTH_JSON_DOCS;
#if SM_WAVE_BUILD
  info.wave_build = true;
#ifdef SM_WAVE_VCD
  info.wave_vcd = true;
#else
  info.wave_vcd = false;
#endif
#ifdef SM_WAVE_FST
  info.wave_fst = true;
#endif
#endif
  const auto run = [](const RunRequest& req, RunResult& out) {
#if SM_WAVE_BUILD
#ifdef SM_WAVE_FST
    if (req.wave_fmt == "fst") return run_model<SM_WAVE_FST>(req, out);
#endif
#ifdef SM_WAVE_VCD
    if (req.wave_fmt == "vcd") return run_model<SM_WAVE_VCD>(req, out);
#endif
    fail(fmt::format("this simulator does not write .{} waves", req.wave_fmt));
#else
    return run_model<SM_VTOP>(req, out);
#endif
  };
  return sm::simapp::run_stereo_sim(argc, argv, info, run,
                                    [](const std::string& path) { return sm::wave_signal_names(path); });
}
