// stereo_sim's register plan (sm_sim_regplan.hpp).
#include "sm_sim_regplan.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "calib_file.hpp"
#include "pipeline.hpp"
#include "toolio/sm_regs_json.hpp"
#include "sm_sim_preflight.hpp"
#include "lower_case.hpp"

namespace sm::simapp {

namespace {

// The compile-time keys of a register file (`got`) must be this simulator's (`hw`).
void check_hw_keys(const std::string& path, const HwConfig& got, const HwConfig& hw) {
  const auto want = hw.parameters();
  for (const auto& [name, g] : got.parameters())
    if (g != want.at(name))
      fail(fmt::format("{}: '{}' = {}, but this simulator is built with {}", path, lower_case(name), g, want.at(name)));
}

// A calibration file this IP can hold; a folder named as the file gets
// "<path>: is a directory", not a stream error.
CalibFile load_sim_calib(const std::string& path, const HwConfig& hw) {
  check_readable_file("", path);
  return load_fitting_calib(path, hw);
}

// A register file on top of `r` (frame `what`): the compile-time keys must be this
// simulator's, the active size may only be set where `size_ok`, a calibration is applied.
// Returns whether the file had a calibration.
bool apply_regs_file(const std::string& path, const HwConfig& hw, Regs& r, bool size_ok) {
  HwConfig h = hw;
  const int w0 = r.width, h0 = r.height;
  const tools::RegsFile rf = tools::apply_regs_json(path, h, r);
  check_hw_keys(path, h, hw);
  if (!size_ok && (r.width != w0 || r.height != h0))
    fail(fmt::format("{}: '{}' = {}: the active size ({}x{}) cannot change within a run", path,
                     r.width != w0 ? "width" : "height", r.width != w0 ? r.width : r.height, w0, h0));
  if (!rf.calib.empty()) {
    try {
      apply_calib(load_sim_calib(rf.calib, hw), r);
    } catch (const std::exception& e) {
      fail(fmt::format("{}: 'calib' {}: {}", path, rf.calib, e.what()));
    }
  }
  return !rf.calib.empty();
}

// --regs on top of the defaults; --width / --height win over the file's active size.
void apply_base_file(const SimOptions& opt, const HwConfig& hw, Regs& base) {
  const int w0 = base.width, h0 = base.height;
  const bool file_calib = apply_regs_file(opt.regs_file, hw, base, true);
  if (opt.width_given) base.width = opt.width;
  if (opt.height_given) base.height = opt.height;
  const int width = base.width, height = base.height;
  if (file_calib && (base.grid_l.gw != RectGrid::points_w(width) || base.grid_l.gh != RectGrid::points_h(height)))
    fail(fmt::format("{}: its calibration is for another size than the active {}x{}", opt.regs_file, width, height));
  if (!file_calib && (width != w0 || height != h0)) {
    base.grid_l = RectGrid::identity(width, height);
    base.grid_r = base.grid_l;
  }
}

// The registers written before the first frame.
Regs base_registers(const SimOptions& opt, const HwConfig& hw) {
  Regs base = Regs::defaults(hw);
  base.width = opt.width;
  base.height = opt.height;
  base.grid_l = RectGrid::identity(opt.width, opt.height);
  base.grid_r = base.grid_l;
  if (!opt.regs_file.empty()) apply_base_file(opt, hw, base);
  if (!opt.calib.empty()) apply_calib(load_sim_calib(opt.calib, hw), base);
  opt.apply_reg_options(hw, base);  // a value out of range: a ToolError, one line like fail()
  return base;
}

// The schedule: FRAME=FILE entries, applied in frame order (command-line order within a frame).
std::vector<std::pair<int, std::string>> parse_schedule(const SimOptions& opt) {
  std::vector<std::pair<int, std::string>> sched;
  for (const std::string& e : opt.regs_at) {
    const size_t eq = e.find('=');
    int f = -1;
    if (eq == std::string::npos || eq == 0 || eq + 1 == e.size() || !CLI::detail::lexical_cast(e.substr(0, eq), f) ||
        f < 0)
      fail(fmt::format("--regs-at {}: expected FRAME=FILE with FRAME >= 0", e));
    if (f >= opt.frames)
      fail(fmt::format("--regs-at {}: frame {} is beyond the {} frame(s) streamed", e, f, opt.frames));
    sched.emplace_back(f, e.substr(eq + 1));
  }
  std::stable_sort(sched.begin(), sched.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return sched;
}

}  // namespace

RegisterPlan plan_registers(const SimOptions& opt, const HwConfig& hw) {
  RegisterPlan p;
  const Regs base = base_registers(opt, hw);
  p.width = base.width;
  p.height = base.height;
  p.sched = parse_schedule(opt);
  p.regs.assign(static_cast<size_t>(opt.frames), base);
  size_t k = 0;
  for (int f = 0; f < opt.frames; ++f) {
    if (f > 0) p.regs[f] = p.regs[f - 1];
    for (; k < p.sched.size() && p.sched[k].first == f; ++k) apply_regs_file(p.sched[k].second, hw, p.regs[f], false);
  }
  for (size_t f = 0; f < p.regs.size(); ++f) {
    try {
      validate_regs(p.regs[f], hw);
    } catch (const std::invalid_argument& e) {
      fail(fmt::format("registers of frame {}: {}", f, e.what()));
    }
  }
  return p;
}

void fit_plan_to_input(RegisterPlan& plan, size_t nframes) {
  if (!plan.sched.empty() && plan.sched.back().first >= static_cast<int>(nframes))
    fail(fmt::format("--regs-at {}={}: the input has only {} frame(s)", plan.sched.back().first,
                     plan.sched.back().second, nframes));
  plan.regs.resize(nframes);
}

HostSchedule schedule_host_writes(const RegisterPlan& plan, const HwConfig& hw, bool late) {
  HostSchedule s;
  s.ops = plan_register_schedule(plan.regs, hw, late, &s.frames);
  return s;
}

}  // namespace sm::simapp
