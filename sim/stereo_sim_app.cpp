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
// sm_sim_check, sm_sim_report, sm_sim_outputs, sm_sim_depth, sm_sim_pictures.
#include "stereo_sim_app.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_outputs.hpp"
#include "sm_sim_check.hpp"
#include "sm_sim_depth.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_options.hpp"
#include "sm_sim_outputs.hpp"
#include "sm_sim_pictures.hpp"
#include "sm_sim_preflight.hpp"
#include "sm_sim_regplan.hpp"
#include "sm_sim_report.hpp"
#include "sm_sim_shards.hpp"
#include "sm_sim_simulate.hpp"

namespace sm::simapp {

namespace {

// Every output of the run, staged and committed together (all or none): the pictures,
// --disp-file, the depth outputs, the panel and report.json.
void write_outputs(const SimOptions& opt, const HwConfig& hw, const SimInput& in, const RegisterPlan& plan,
                   const ModelCheck& check, const SimCamera& cam, const cv::Mat& disp, const SimReport& rep) {
  const RectCamera* camera = cam.camera ? &*cam.camera : nullptr;
  const tools::ColourRange range = picture_range(in, disp);
  const PipelineResult model = last_frame_model(hw, plan, check);
  tools::OutputSet outs;
  write_disparity_pictures(outs, opt.out_dir, disp, hw, range, camera);
  write_disparity_files(outs, opt, disp);
  write_depth_outputs(outs, opt, cam, disp, model.rl);
  write_panel(outs, opt.out_dir,
              {&in, &check.last_input, &model, &disp, range, &rep.packets, camera, opt.depth.cloud_max_depth,
               rep.json.value("bad1_percent", 0.0)});
  outs.write(
      opt.out_dir + "/report.json", [&](const std::string& t) { tools::write_json_atomic(t, rep.json); }, true);
  outs.commit();
}

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
  // every file and folder before any work: a bad one simulates nothing, writes nothing
  check_disp_file_option(opt);
  check_files(opt);
  const SimCamera cam = resolve_camera(opt, hw);  // before the plan: a scene's calib.json is its --calib
  // the input's frames counted (none read): a sequence or video runs all of them unless
  // --frames limits it; registers before any frame is read: a bad file simulates nothing
  SimInput in = open_inputs(opt);
  opt.frames = static_cast<int>(in.nframes);
  RegisterPlan plan = plan_registers(opt, hw);
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
  // a warning, not progress: shown with -q too
  if (in.source->resized())
    fmt::print(stderr, "note: input resized to the active size {}x{}\n", plan.width, plan.height);
  const ModelCheck& check = run.check;
  const cv::Mat disp = tools::out_to_float(run.last);
  SimReport rep = make_report(opt, info, in, plan, run, check, disp);
  add_calibration_report(cam, rep.json);
  if (opt.shard.given) add_shard_info(opt, in, rep.status_lines, rep.json);
  write_outputs(opt, hw, in, plan, check, cam, disp, rep);
  print_report(opt, hw, in, plan, run, check, rep);
  if (!cam.note.empty()) fmt::print("calibration: {}\n", cam.note);
  return report_exit_code(opt, run, check, rep);
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
