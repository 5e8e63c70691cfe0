// stereo_sim's simulation stage (sm_sim_simulate.hpp).
#include "sm_sim_simulate.hpp"

#include <fmt/format.h>

#include "sm_sim_outputs.hpp"

namespace sm::simapp {

namespace {

void check_wave_window(const SimOptions& opt, size_t nframes, int height) {
  if (!opt.wave_path.empty() && opt.vcd_frame >= static_cast<int>(nframes))
    fail(fmt::format("--vcd-frame {}: the input has only {} frame(s)", opt.vcd_frame, nframes));
  if (!opt.wave_path.empty() && opt.vcd_line >= height)
    fail(fmt::format("--vcd-line {}: the active height is {}", opt.vcd_line, height));
}

CameraTiming camera_timing(const SimOptions& opt, int fold, int width, int height) {
  CameraTiming timing;
  timing.continuous = opt.continuous;
  timing.hblank = opt.hblank;
  timing.vblank_lines = opt.vblank;
  timing.pixel_clock_hz = opt.pixel_clock;
  timing.set_core(fold, opt.core_mhz, width, height);
  if (opt.core_mhz > 0 && timing.core_hz < timing.clock_hz(width, height))
    fail(fmt::format("--core-mhz {}: below the camera's pixel clock {:.3f} MHz", opt.core_mhz,
                     timing.clock_hz(width, height) / 1e6));
  return timing;
}

void set_wave_request(const SimOptions& opt, RunRequest& req) {
  req.wave_fmt = opt.wave_fmt;
  req.list_scopes = opt.wave_list_scopes;
  req.wave_scopes = opt.wave_scopes;
  req.wave_depth = opt.wave_depth;
  req.window.path = opt.wave_path;
  req.window.frame = opt.vcd_frame;
  req.window.line = opt.vcd_line;
  req.window.lines = opt.vcd_lines;
  req.window.cycles = opt.vcd_cycles;
  for (const auto& sc : opt.wave_scopes) req.window.scope.scopes.push_back({sc, opt.wave_depth});
}

}  // namespace

SimRun simulate(const SimOptions& opt, const HwConfig& hw, SimInput& in, const RegisterPlan& plan,
                const RunFn& run_model) {
  check_wave_window(opt, in.nframes, plan.height);
  SimRun run;
  const HostSchedule host = schedule_host_writes(plan, hw, opt.late_regs);
  run.host = plan.host_report.empty() ? host.frames : plan.host_report;
  run.fold = hw.clocks_per_beat();
  run.timing = camera_timing(opt, run.fold, plan.width, plan.height);
  run.check = start_check(opt.no_check, in.first, in.nframes);
  FrameWindow window(*in.source);
  FrameFiles each(opt.disp_file);
  RunRequest req;
  req.feed.count = in.nframes;
  req.feed.frame = [&window](size_t f) -> const StereoFrame& { return window.at(f); };
  req.feed.out = [&](size_t f, OutImage&& disp) {
    check_frame(run.check, f, hw, plan.regs[f], window.at(f), disp);
    if (opt.disp_each) each.write(in.first + f, disp);
    window.release(f + 1);
    if (f + 1 == in.nframes) run.last = std::move(disp);
  };
  req.width = plan.width;
  req.height = plan.height;
  req.timing = run.timing;
  req.regs0 = &plan.regs[0];
  req.host = &host.ops;
  req.quiet = opt.quiet;
  set_wave_request(opt, req);
  run.ran = run_model(req, run.out);
  if (!run.ran) return run;
  check_packets(run.check, run.out.res);
  each.keep();
  return run;
}

}  // namespace sm::simapp
