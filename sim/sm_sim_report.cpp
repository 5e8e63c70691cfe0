// stereo_sim's report (sm_sim_report.hpp).
#include "sm_sim_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_object_flags.hpp"
#include "toolio/sm_objects_json.hpp"
#include "sm_regmap.hpp"
#include "sm_regs_io.hpp"
#include "sm_sim_preflight.hpp"
#include "lower_case.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace sm::simapp {

namespace {

// The register values of a frame, by the register file's key names.
json regs_json(const Regs& r, int grid_bank) {
  json j;
  for (const RegWord& w : register_words(r)) {
    const std::string k = lower_case(w.name);
    j[k] = (k == "offset_l" || k == "offset_r") ? json(static_cast<int32_t>(w.value)) : json(w.value);
  }
  j["grid_bank"] = grid_bank;
  return j;
}

json object_json(const ObjectPacket& p) {
  json j = {{"valid", p.valid}, {"count", p.objects.size()}, {"too_many", p.too_many}, {"table_full", p.table_full},
            {"lost", p.lost},   {"objects", json::array()},  {"notes", p.notes}};
  for (const auto& o : p.objects) {
    json b = tools::object_box_json(o);
    b.update(json{{"pixels", o.count}, {"sum_disp", o.sum_disp}, {"nearest_disp", o.max_disp}});
    j["objects"].push_back(b);
  }
  return j;
}

// The status and error registers read back, field by field: report.json's "status" and
// one text line per register.
json decode_status(const RunResult& run, std::vector<std::string>& lines) {
  json status;
  for (const auto& [ri, word] : run.status) {
    const auto& reg = regmap::registers()[ri];
    const std::string name = reg.name;
    json j = {{"word", word}};
    std::string line = fmt::format("{:<13} 0x{:08x}", name, word);
    for (int i = 0; i < reg.num_fields; ++i) {
      const auto& fd = regmap::fields()[static_cast<size_t>(reg.first_field + i)];
      const std::string fname = std::string(fd.name).substr(name.size() + 1);
      const uint32_t v = (word & fd.mask()) >> fd.lsb;
      j[fname] = v;
      line += fmt::format("  {} {}", fname, v);
    }
    status[name] = j;
    lines.push_back(line);
  }
  return status;
}

// The steady-state frame period: the mean interval between the last output pixels of
// consecutive frames, over the frames followed by another one (frames 0..n-2). The last
// frame is left out: no input follows it, so it drains without the next frame's lines
// and ends early (a 4-frame run measured 103680 cycles with it, below the camera's
// frame). 0 with fewer than 3 frames.
uint64_t steady_period(const std::vector<FrameStats>& st) {
  if (st.size() < 3) return 0;
  const size_t last = st.size() - 2;  // the last frame with a successor
  return (st[last].last_out_cycle - st[0].last_out_cycle + last / 2) / last;
}

FrameFigures frame_figures(const SimOptions& opt, const RegisterPlan& plan, const SimRun& run, const json& status) {
  const SimResult& res = run.out.res;
  const CameraTiming& timing = run.timing;
  const int width = plan.width, height = plan.height, fold = run.fold;
  FrameFigures g;
  const auto& s0 = res.stats.front();
  g.frame_cycles = s0.last_out_cycle - s0.sof_in_cycle + 1;
  g.input_cycles = s0.last_in_cycle - s0.sof_in_cycle + 1;
  g.tail_cycles = s0.last_out_cycle - s0.last_in_cycle;
  g.latency = s0.first_out_cycle - s0.sof_in_cycle;
  g.camera_clock = timing.clock_hz(width, height);
  const double aclk_per_cam = timing.aclk_per_camera_clock(width, height);
  g.core_hz = timing.aclk_hz(width, height);
  g.line_period = (width + (opt.continuous ? 0 : opt.hblank)) * aclk_per_cam;
  g.period = steady_period(res.stats);
  g.pixels = static_cast<uint64_t>(width) * height;
  // The IP needs F = DISP / PU clocks per pixel in steady state; its own rate bounds the clock.
  g.ip_cycles_per_frame =
      std::max<uint64_t>(g.pixels * fold, opt.continuous && timing.core_hz == 0 ? g.period : g.pixels * fold);
  g.min_clock_30 = 30.0 * static_cast<double>(g.ip_cycles_per_frame);
  // With this camera: its pixels must not arrive faster than one per F aclk cycles
  // (sm_seq's input FIFO rule, docs/streams.md "Pacing"). That holds whatever the blanking;
  // with the blanking the FIFO absorbs, a slower clock can do (fps_ok measures it).
  g.min_core_camera = fold * g.camera_clock;
  const double camera_period = (opt.continuous ? static_cast<double>(g.pixels)
                                               : static_cast<double>(width + opt.hblank) * (height + opt.vblank)) *
                               aclk_per_cam;
  g.fifo_max = status.contains("IN_FIFO") ? status["IN_FIFO"]["LEVEL_MAX"].get<uint64_t>() : 0;
  g.fps_ok =
      res.input_stall_cycles == 0 && (g.period == 0 || static_cast<double>(g.period) <= std::ceil(camera_period));
  return g;
}

json config_json(const HwConfig& hw, const RegisterPlan& plan) {
  json c = {{"max_width", hw.max_width},
            {"max_height", hw.max_height},
            {"disp", hw.disp},
            {"census", hw.census},
            {"sw", hw.sw},
            {"rect_radius", hw.rect_radius},
            {"max_objects", hw.max_objects},
            {"width", plan.width},
            {"height", plan.height}};
  c["pu"] = hw.levels_per_clock();
  return c;
}

void add_timing(const SimOptions& opt, const SimRun& run, const FrameFigures& g, json& rep) {
  rep["timing"] = {{"continuous", opt.continuous},
                   {"hblank", opt.continuous ? 0 : opt.hblank},
                   {"vblank_lines", opt.continuous ? 0 : opt.vblank},
                   {"camera_pixel_clock_hz", g.camera_clock},
                   {"core_clock_hz", g.core_hz}};
  rep["clocks_per_pixel"] = run.fold;
  rep["min_core_clock_hz_this_camera"] = g.min_core_camera;
  rep["input_fifo_level_max"] = g.fifo_max;
  rep["cycles_per_frame_sof_to_last_pixel"] = g.frame_cycles;
  rep["input_cycles_per_frame"] = g.input_cycles;  // sof in -> last pixel in: W*H + camera blanking
  rep["camera_blanking_cycles_per_frame"] = g.input_cycles - std::min(g.input_cycles, g.pixels);
  rep["last_pixel_in_to_out_cycles"] = g.tail_cycles;
  rep["steady_state_frame_period_cycles"] = g.period;
  rep["latency_cycles"] = g.latency;
  rep["latency_lines"] = static_cast<double>(g.latency) / g.line_period;
  rep["input_stall_cycles"] = run.out.res.input_stall_cycles;
  rep["min_clock_hz_for_30fps"] = g.min_clock_30;
  rep["fps_at_clock"] = {{"clock_mhz", opt.clock_mhz},
                         {"fps", opt.clock_mhz * 1e6 / static_cast<double>(g.ip_cycles_per_frame)}};
  rep["meets_30fps_with_camera_at_core_clock"] = g.fps_ok;
}

void add_check(const RegisterPlan& plan, const SimResult& res, const ModelCheck& check, json& rep) {
  rep["framing_ok"] = res.framing_error.empty();
  if (!res.framing_error.empty()) rep["framing_error"] = res.framing_error;
  rep["bit_exact"] = !check.done ? json(nullptr) : json(check.mismatches == 0);
  rep["mismatches"] = check.mismatches;
  if (check.mismatches) rep["first_mismatch"] = check.first_mismatch;
  rep["register_schedule"] = {
      {"files", json::array()}, {"axi_writes", res.host_writes}, {"ok", res.host_errors.empty()}};
  for (const auto& [f, file] : plan.sched) rep["register_schedule"]["files"].push_back({{"frame", f}, {"file", file}});
  if (!res.host_errors.empty()) rep["register_schedule"]["errors"] = res.host_errors;
}

// Per frame: its registers, what the host changed for it, the RTL's object packet.
json frame_results(const HwConfig& hw, const RegisterPlan& plan, const SimRun& run, const ModelCheck& check,
                   std::vector<ObjectPacket>& packets) {
  const SimResult& res = run.out.res;
  json frames = json::array();
  for (size_t f = 0; f < plan.regs.size(); ++f) {
    json fr = {{"frame", plan.first + f},
               {"registers", regs_json(plan.regs[f], run.host[f].grid_bank)},
               {"changed", run.host[f].changed}};
    if (f < res.object_packets.size()) {
      packets.push_back(decode_object_packet(res.object_packets[f].words));
      if (!res.object_packets[f].words.empty())
        packets.back().notes = tools::object_flag_lines(res.object_packets[f].words[0], hw, plan.regs[f]);
      fr["object_packet"] = object_json(packets.back());
    } else {
      fr["object_packet"] = nullptr;
    }
    if (check.done) fr["bit_exact"] = check.frame_mismatches[f] == 0;
    if (f < res.stats.size()) {
      const FrameStats& st = res.stats[f];
      fr["cycles"] = {{"sof_in", st.sof_in_cycle},
                      {"last_in", st.last_in_cycle},
                      {"first_out", st.first_out_cycle},
                      {"last_out", st.last_out_cycle}};
    }
    frames.push_back(fr);
  }
  return frames;
}

// Synthesis figures: the given report (it must be valid), else the one `synth_paper` /
// `synth_small` built for this configuration, else the one committed in docs/synth.
void add_synthesis(const SimOptions& opt, const ModelInfo& info, json& rep) {
  std::string path = opt.synth_json;
  const bool given = !path.empty();
  if (!given) {
    for (const std::string& cand : {info.synth_json, info.synth_json_docs})
      if (fs::exists(cand)) {
        path = cand;
        break;
      }
  }
  if (path.empty()) return;
  try {
    rep["synthesis"] = read_synthesis_total(path);  // a given report was checked before the run
    rep["synthesis_report"] = path;
  } catch (const std::exception& e) {
    if (given) throw;
    fmt::print(stderr, "note: {}, ignored\n", e.what());
  }
}

}  // namespace

json invalid_json(const tools::FailCounts& c) {
  json j = {{"pixels", c.invalid}, {"of", c.pixels}};
  for (int k = 0; k < tools::FailCounts::kN; ++k) j[tools::FailCounts::kRules[k]] = c.by_rule[k];
  return j;
}

std::string invalid_line(const json& j) {
  tools::FailCounts c;
  c.invalid = j.at("pixels").get<long>();
  c.pixels = j.at("of").get<long>();
  for (int k = 0; k < tools::FailCounts::kN; ++k) c.by_rule[k] = j.at(tools::FailCounts::kRules[k]).get<long>();
  return tools::fail_counts_line(c);
}

SimReport make_report(const SimOptions& opt, const ModelInfo& info, const SimInput& in, const RegisterPlan& plan,
                      const SimRun& run, const ModelCheck& check, const cv::Mat& disp) {
  SimReport r;
  const json status = decode_status(run.out, r.status_lines);
  r.fig = frame_figures(opt, plan, run, status);
  json& rep = r.json;
  const size_t nframes = in.nframes;
  const double wall = run.out.wall;
  rep["input"] = in.name;
  rep["frames_note"] = in.source->note();
  rep["config"] = config_json(info.hw, plan);
  rep["frames"] = nframes;
  add_timing(opt, run, r.fig, rep);
  add_check(plan, run.out.res, check, rep);
  rep["frame_results"] = frame_results(info.hw, plan, run, check, r.packets);
  rep["invalid"] = invalid_json(tools::fail_counts(run.last));
  rep["status"] = status;
  rep["sim_wall_seconds"] = wall;
  rep["sim_frames_per_second"] = nframes / wall;
  rep["sim_cycles_per_second"] = run.out.res.cycles / wall;
  if (!in.gt.empty()) {
    rep["bad1_percent"] = tools::bad1(disp, in.gt, in.mask).bad_pct();
    rep["ground_truth"] = {{"resized", !in.gt_note.empty()}, {"disparity_scale", in.gt_scale}};
    if (!in.gt_note.empty()) rep["ground_truth"]["note"] = in.gt_note;
  }
  add_synthesis(opt, info, rep);
  rep["disparity_file"] = opt.disp_file;
  return r;
}

namespace {

void print_figures(const SimOptions& opt, const HwConfig& hw, const SimRun& run, const FrameFigures& g) {
  const SimResult& res = run.out.res;
  fmt::print(
      "  cycles per frame (sof in -> last pixel out): {} = {} input (W*H = {} pixels + {} {}) + {} "
      "last pixel in -> out\n",
      g.frame_cycles, g.input_cycles, g.pixels, g.input_cycles - std::min(g.input_cycles, g.pixels),
      run.timing.core_hz > 0 ? "cycles between them: camera cadence and blanking" : "camera blanking", g.tail_cycles);
  if (g.period)
    fmt::print("  steady-state frame period: {} cycles (frames followed by another; the last one drains)\n", g.period);
  else
    fmt::print("  steady-state frame period: not measured (needs 3 frames or more)\n");
  fmt::print("  latency (sof in -> first pixel out): {} cycles = {:.2f} lines\n", g.latency,
             static_cast<double>(g.latency) / g.line_period);
  fmt::print("  clocks per pixel: {} (DISP {} / PU {}); core clock {:.3f} MHz, camera pixel clock {:.3f} MHz\n",
             run.fold, hw.disp, hw.levels_per_clock(), g.core_hz / 1e6, g.camera_clock / 1e6);
  fmt::print("  input stalls: {} cycles; input FIFO high-water mark: {} pixels\n", res.input_stall_cycles, g.fifo_max);
  fmt::print(
      "  minimum core clock for 30 frames/s: {:.3f} MHz (F x W x H x 30); with this camera {:.3f} MHz whatever "
      "its blanking (F x its pixel clock; the line below is this run's verdict); at {} MHz: {:.1f} frames/s\n",
      g.min_clock_30 / 1e6, g.min_core_camera / 1e6, opt.clock_mhz,
      opt.clock_mhz * 1e6 / static_cast<double>(g.ip_cycles_per_frame));
  fmt::print("  30 frames/s with this camera at this core clock ({:.3f} MHz): {}\n", g.core_hz / 1e6,
             g.fps_ok ? "yes" : "NO");
}

void print_check(const SimOptions& opt, const RegisterPlan& plan, const SimResult& res, const ModelCheck& check) {
  fmt::print("  framing: {}\n", res.framing_error.empty() ? "ok" : res.framing_error);
  if (check.done)
    fmt::print(
        "  bit-exact vs model: {}{}\n", check.mismatches == 0 ? "yes" : "NO, ",
        check.mismatches == 0 ? "" : fmt::format("{} mismatches, first: {}", check.mismatches, check.first_mismatch));
  if (!plan.sched.empty() || opt.late_regs)
    fmt::print("  register schedule: {} file(s), {} AXI4-Lite writes while streaming{}{}\n", plan.sched.size(),
               res.host_writes, opt.late_regs ? " (deliberately one frame late)" : "",
               res.host_errors.empty() ? "" : "; " + res.host_errors.front());
}

}  // namespace

void print_report(const SimOptions& opt, const HwConfig& hw, const SimInput& in, const RegisterPlan& plan,
                  const SimRun& run, const ModelCheck& check, const SimReport& rep) {
  const size_t nframes = in.nframes;
  const json& j = rep.json;
  fmt::print("stereo_sim: {} frame(s) of {}x{}, DISP {}, census {}x{}, SW {}x{}\n", nframes, plan.width, plan.height,
             hw.disp, hw.census, hw.census, hw.sw, hw.sw);
  fmt::print("  input: {}\n", in.source->note());
  print_figures(opt, hw, run, rep.fig);
  print_check(opt, plan, run.out.res, check);
  print_objects(j["frame_results"]);
  fmt::print("  status read back over AXI4-Lite:\n");
  for (const auto& l : rep.status_lines) fmt::print("    {}\n", l);
  fmt::print("  last frame: {}\n", invalid_line(j["invalid"]));
  if (j.contains("bad1_percent"))
    fmt::print("  bad-1.0 vs ground truth: {:.2f} %{}\n", j["bad1_percent"].get<double>(),
               in.gt_note.empty() ? "" : " (" + in.gt_note + ")");
  if (j.contains("synthesis")) {
    const json& t = j["synthesis"];
    fmt::print("  synthesis: {} LUTs ({} LUT-RAM, {} SRL), {} FFs, {} RAMB36, {} DSP, {} LUT levels  [{}]\n",
               t.value("luts", 0), t.value("lutram", 0), t.value("srl", 0), t.value("ffs", 0), t.value("bram36", 0.0),
               t.value("dsp", 0), t.value("lut_levels", 0), j["synthesis_report"].get<std::string>());
  }
  const double wall = run.out.wall;
  fmt::print("  simulation: {:.2f} s wall, {:.2f} frames/s, {:.0f} cycles/s\n", wall, nframes / wall,
             run.out.res.cycles / wall);
  fmt::print("  outputs in {}/ (lossless disparity: {})\n", opt.out_dir, opt.disp_file);
}

void print_objects(const json& frame_results) {
  fmt::print("  objects (from m_axis_obj):\n");
  for (const auto& fr : frame_results) {
    std::string changed;
    for (const auto& c : fr["changed"]) changed += (changed.empty() ? "" : ",") + c.get<std::string>();
    const json& p = fr["object_packet"];
    if (p.is_null()) {
      fmt::print("    frame {}: no packet\n", fr["frame"].get<size_t>());
      continue;
    }
    fmt::print("    frame {}: {} object(s){}{}{}{}{}{}\n", fr["frame"].get<size_t>(), p["objects"].size(),
               p["too_many"].get<bool>() ? ", TOO-MANY" : "", p["table_full"].get<bool>() ? ", TABLE-FULL" : "",
               p["lost"].get<bool>() ? ", LOST (a packet before was dropped)" : "",
               p["valid"].get<bool>() ? "" : ", MALFORMED packet",
               fr.value("bit_exact", true) ? "" : ", differs from model",
               changed.empty() ? "" : "  [changed: " + changed + "]");
    for (size_t i = 0; i < p["objects"].size(); ++i) {
      const json& o = p["objects"][i];
      fmt::print("      #{} x {}..{} y {}..{}  {} px  mean d {}  nearest d {}\n", i, o["x0"].get<int>(),
                 o["x1"].get<int>(), o["y0"].get<int>(), o["y1"].get<int>(), o["pixels"].get<int64_t>(),
                 o["mean_disp"].get<int>(), o["nearest_disp"].get<int>());
    }
    for (const auto& n : p["notes"]) fmt::print("      {}\n", n.get<std::string>());
  }
}

int report_exit_code(const SimOptions& opt, const SimRun& run, const ModelCheck& check, const SimReport& rep) {
  const SimResult& res = run.out.res;
  if (check.mismatches != 0 || !res.framing_error.empty() || !res.host_errors.empty()) return 1;
  return opt.core_mhz_given && !rep.fig.fps_ok ? 3 : 0;
}

}  // namespace sm::simapp
