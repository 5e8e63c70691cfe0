// stereo_sim: cycle-accurate simulation of the stereo IP (Verilated sm_top). Streams a
// stereo pair, a sequence, a video or the built-in synthetic scene through the IP with a
// camera's timing, checks every output pixel and the object list against the reference
// model, and reports cycles, the 30 frames/s budget, accuracy and area. Every run-time
// register can be set (--regs) and changed frame by frame (--regs-at): the harness writes
// the changes over AXI4-Lite while the camera streams, as a host would; the report lists
// each frame's object packet and the status read back at the end. A wave window
// (--wave FILE.vcd|FILE.fst) dumps sm_top's signals, or one block's (--wave-scope, in the
// full-depth wave builds stereo_sim_wave / stereo_sim_small_wave).
// This file is the part compiled once; the Verilated model's run is stereo_sim.cpp
// (stereo_sim_app.hpp). The run's stages, in the order the data flows through them, are
// each in their own file: sm_sim_options, sm_sim_regplan, sm_sim_inputs, sm_sim_simulate,
// sm_sim_check, sm_sim_report, sm_sim_outputs, sm_sim_pictures.
#include "stereo_sim_app.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "toolio/sm_io.hpp"
#include "sm_sim_check.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_options.hpp"
#include "sm_sim_outputs.hpp"
#include "sm_sim_pictures.hpp"
#include "sm_sim_regplan.hpp"
#include "sm_sim_report.hpp"
#include "sm_sim_shards.hpp"
#include "sm_sim_simulate.hpp"

namespace sm::simapp {

namespace {

// Everything after the options were parsed; throws on error.
int run_stages(const ModelInfo& info, const RunFn& run_model, const WaveNamesFn& wave_names, SimOptions& opt) {
  const HwConfig& hw = info.hw;
  if (!opt.wave_list.empty()) {
    for (const auto& n : wave_names(opt.wave_list)) fmt::print("{}\n", n);
    return 0;
  }
  check_wave_options(info, opt);
  tools::quiet_opencv();
  if (!opt.shard.merge.empty()) return merge_shard_dirs(opt.shard.merge, opt.out_dir, opt.quiet);
  // the input's frames counted (none read): a sequence or video runs all of them unless
  // --frames limits it; registers before any frame is read: a bad file simulates nothing
  SimInput in = open_inputs(opt);
  opt.frames = static_cast<int>(in.nframes);
  RegisterPlan plan = plan_registers(opt, hw);
  check_disp_file_option(opt);
  fit_plan_to_input(plan, in.nframes);
  if (opt.shard.list_shards > 0) {
    for (const auto& r : shard_ranges(in.nframes, opt.shard.list_shards)) fmt::print("{}\n", r);
    return 0;
  }
  if (opt.shard.jobs > 1) return run_jobs(opt, in.nframes);
  fit_inputs(opt, plan.width, plan.height, in);
  if (opt.shard.given) start_shard(opt, hw, plan, in);
  const SimRun run = simulate(opt, hw, in, plan, run_model);
  if (!run.ran) return 0;  // --wave-scopes
  if (in.source->resized() && !opt.quiet)
    fmt::print(stderr, "note: input resized to the active size {}x{}\n", plan.width, plan.height);
  const ModelCheck& check = run.check;
  const cv::Mat disp = tools::disp_to_float(run.last);
  SimReport rep = make_report(opt, info, in, plan, run, check, disp);
  if (opt.shard.given) add_shard_info(opt, in, rep.json);
  std::filesystem::create_directories(opt.out_dir);
  write_disparity_pictures(opt.out_dir, disp, hw);
  write_disparity_files(opt, disp);
  write_panel(opt.out_dir, hw, in, plan, check, rep.packets, disp, rep.json.value("bad1_percent", 0.0));
  tools::write_text_atomic(opt.out_dir + "/report.json", rep.json.dump(2) + "\n");
  print_report(opt, hw, in, plan, run, check, rep);
  return report_exit_code(run, check);
}

}  // namespace

int run_stereo_sim(int argc, char** argv, const ModelInfo& info, const RunFn& run_model,
                   const WaveNamesFn& wave_names) {
  SimOptions opt;
  if (const auto rc = parse_sim_options(argc, argv, info, opt)) return *rc;
  try {
    return run_stages(info, run_model, wave_names, opt);
  } catch (const std::exception& e) {
    fmt::print(stderr, "stereo_sim: error: {}\n", e.what());
    return 2;
  }
}

}  // namespace sm::simapp
