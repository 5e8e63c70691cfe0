// stereo_sim: cycle-accurate simulation of the stereo IP (Verilated sm_top). Streams a
// stereo pair, a sequence, a video or the built-in synthetic scene through the IP with a
// camera's timing, checks every output pixel and the object list against the reference
// model, and reports cycles, the 30 frames/s budget, accuracy and area.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "calib_file.hpp"
#include "pipeline.hpp"
#include "common/sm_io.hpp"
#include "sm_regs_io.hpp"
#include "sm_sim.hpp"
#include "sm_vconfig.hpp"
#include SM_VTOP_H

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct Input {
  std::vector<std::pair<sm::Image8, sm::Image8>> frames;
  cv::Mat gt;    // CV_32F disparity, 0 = unknown (empty when none)
  cv::Mat mask;  // 8-bit evaluation mask (empty: all known gt)
  std::string name;
};

[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

sm::Image8 to_size(const cv::Mat& grey, int w, int h, const std::string& what, bool* resized) {
  cv::Mat g = grey;
  if (g.cols != w || g.rows != h) {
    cv::resize(grey, g, cv::Size(w, h), 0, 0, cv::INTER_AREA);
    *resized = true;
  }
  (void)what;
  return sm::tools::to_image8(g);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cycle-accurate simulation of the census stereo IP (Verilator)"};
  const sm::HwConfig hw = sm::verilated_config();
  std::string left, right, seq_dir, video, scene_dir = SM_DEFAULT_SCENE, calib, out_dir = "out", synth_json, vcd_path;
  int frames_n = 2, width = hw.max_width, height = hw.max_height;
  int hblank = 80, vblank = 22;
  bool continuous = false, quiet = false, no_check = false;
  double pixel_clock = 0, clock_mhz = 100.0;
  int vcd_frame = 0, vcd_line = 0, vcd_lines = 4;
  uint64_t vcd_cycles = 0;
  int occ = -1, filters = -1;
  app.add_option("--left", left, "left image (with --right)");
  app.add_option("--right", right, "right image");
  app.add_option("--sequence", seq_dir, "folder of left*/right* image pairs, sorted by name");
  app.add_option("--video", video, "side-by-side stereo video (left half, right half)");
  app.add_option("--scene", scene_dir, "scene folder (left.png right.png [gt.png scale.txt nonocc.png])")
      ->capture_default_str();
  app.add_option("--frames", frames_n, "frames to stream (a pair or scene is repeated)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--width", width, "active width")->check(CLI::Range(16, hw.max_width))->capture_default_str();
  app.add_option("--height", height, "active height")->check(CLI::Range(16, hw.max_height))->capture_default_str();
  app.add_option("--calib", calib, "calibration JSON from sm_calibrate (written over AXI4-Lite)");
  app.add_option("--occ", occ, "occlusion penalty register")->check(CLI::Range(0, 255));
  app.add_option("--filters", filters, "post-processing filter enables (bit mask)")->check(CLI::Range(0, 7));
  app.add_flag("--continuous", continuous, "no blanking: one pixel every clock");
  app.add_option("--hblank", hblank, "camera horizontal blanking (cycles)")->capture_default_str();
  app.add_option("--vblank", vblank, "camera vertical blanking (lines)")->capture_default_str();
  app.add_option("--pixel-clock", pixel_clock, "camera pixel clock in Hz (default: 30 frames/s)");
  app.add_option("--clock-mhz", clock_mhz, "clock for the frames/s figure")->capture_default_str();
  app.add_option("--vcd", vcd_path, "dump a VCD window to this file (e.g. waves/top.vcd)");
  app.add_option("--vcd-frame", vcd_frame, "VCD window: input frame")->capture_default_str();
  app.add_option("--vcd-line", vcd_line, "VCD window: input line")->capture_default_str();
  app.add_option("--vcd-lines", vcd_lines, "VCD window: line periods to dump")->capture_default_str();
  app.add_option("--vcd-cycles", vcd_cycles, "VCD window: cycles to dump (overrides lines)");
  app.add_option("--out", out_dir, "output folder (disparity, panel, report.json)")->capture_default_str();
  app.add_option("--synth-json", synth_json,
                 "synthesis report JSON (default: build/synth, else docs/synth, for this configuration)");
  app.add_flag("--no-check", no_check, "skip the reference-model comparison");
  app.add_flag("-q,--quiet", quiet, "no progress output");
  CLI11_PARSE(app, argc, argv);

  try {
    // ---- input ----
    Input in;
    bool resized = false;
    auto read_grey = [](const std::string& p) { return sm::tools::load_grey_mat(p); };
    if (!left.empty() || !right.empty()) {
      if (left.empty() || right.empty()) fail("--left and --right go together");
      cv::Mat l = read_grey(left), r = read_grey(right);
      if (l.size() != r.size())
        fail(fmt::format("{}: {}x{} does not match {}: {}x{}", left, l.cols, l.rows, right, r.cols, r.rows));
      for (int i = 0; i < frames_n; ++i)
        in.frames.emplace_back(to_size(l, width, height, left, &resized), to_size(r, width, height, right, &resized));
      in.name = left;
    } else if (!seq_dir.empty()) {
      std::vector<fs::path> ls, rs;
      if (!fs::is_directory(seq_dir)) fail(fmt::format("{}: not a folder", seq_dir));
      for (auto& e : fs::directory_iterator(seq_dir)) {
        const auto n = e.path().filename().string();
        if (n.rfind("left", 0) == 0) ls.push_back(e.path());
        if (n.rfind("right", 0) == 0) rs.push_back(e.path());
      }
      std::sort(ls.begin(), ls.end());
      std::sort(rs.begin(), rs.end());
      if (ls.empty() || ls.size() != rs.size())
        fail(fmt::format("{}: {} left* and {} right* images (need equal, non-zero counts)", seq_dir, ls.size(),
                         rs.size()));
      for (size_t i = 0; i < ls.size() && static_cast<int>(i) < frames_n; ++i)
        in.frames.emplace_back(to_size(read_grey(ls[i].string()), width, height, ls[i].string(), &resized),
                               to_size(read_grey(rs[i].string()), width, height, rs[i].string(), &resized));
      in.name = seq_dir;
    } else if (!video.empty()) {
      cv::VideoCapture cap(video);
      if (!cap.isOpened()) fail(fmt::format("{}: cannot open video", video));
      cv::Mat f, g;
      while (static_cast<int>(in.frames.size()) < frames_n && cap.read(f)) {
        if (f.cols < 2) fail(fmt::format("{}: frame too narrow", video));
        if (f.channels() == 3)
          cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
        else
          g = f;
        const int hw2 = g.cols / 2;
        in.frames.emplace_back(to_size(g(cv::Rect(0, 0, hw2, g.rows)), width, height, video, &resized),
                               to_size(g(cv::Rect(hw2, 0, hw2, g.rows)), width, height, video, &resized));
      }
      if (in.frames.empty()) fail(fmt::format("{}: no frames could be read", video));
      in.name = video;
    } else {
      const sm::tools::Scene sc = sm::tools::load_scene(scene_dir);
      const sm::Image8 l = to_size(sc.left, width, height, scene_dir, &resized);
      const sm::Image8 r = to_size(sc.right, width, height, scene_dir, &resized);
      for (int i = 0; i < frames_n; ++i) in.frames.emplace_back(l, r);
      if (!sc.gt.empty() && sc.gt.cols == width && sc.gt.rows == height) {
        in.gt = sc.gt;
        in.mask = sc.nonocc;
      }
      in.name = scene_dir;
    }
    if (resized && !quiet) fmt::print(stderr, "note: input resized to the active size {}x{}\n", width, height);

    // ---- registers ----
    sm::Regs regs = sm::Regs::defaults(hw);
    regs.width = width;
    regs.height = height;
    regs.grid_l = sm::RectGrid::identity(width, height);
    regs.grid_r = regs.grid_l;
    if (!calib.empty()) apply_calib(sm::load_calib(calib), regs);
    if (occ >= 0) regs.occ = static_cast<uint8_t>(occ);
    if (filters >= 0) regs.filter_enable = static_cast<uint8_t>(filters);
    sm::validate_regs(regs, hw);

    // ---- simulate ----
    sm::Testbench<SM_VTOP> tb;
    sm::SimEngine<SM_VTOP> sim(tb);
    sim.reset();
    sm::write_registers(sim.axil(), regs, hw);
    sm::CameraTiming timing;
    timing.continuous = continuous;
    timing.hblank = hblank;
    timing.vblank_lines = vblank;
    timing.pixel_clock_hz = pixel_clock;
    sm::VcdWindow vw;
    if (!vcd_path.empty()) {
      fs::create_directories(fs::path(vcd_path).parent_path().empty() ? fs::path(".")
                                                                      : fs::path(vcd_path).parent_path());
      vw.path = vcd_path;
      vw.frame = vcd_frame;
      vw.line = vcd_line;
      vw.lines = vcd_lines;
      vw.cycles = vcd_cycles;
    }
    const auto t0 = std::chrono::steady_clock::now();
    sim.on_frame = [&](size_t done, size_t total) {
      if (quiet) return;
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print(stderr, "\rsimulated frame {}/{} ({:.1f} s)", done, total, s);
      if (done == total) fmt::print(stderr, "\n");
    };
    const sm::SimResult res = sim.run(in.frames, width, height, timing, vw);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // ---- check against the model ----
    json rep;
    int mismatches = 0;
    std::string first_mismatch;
    std::vector<sm::PipelineResult> model;
    if (!no_check) {
      for (size_t f = 0; f < in.frames.size(); ++f) {
        model.push_back(sm::run_pipeline(in.frames[f].first, in.frames[f].second, hw, regs, false));
        const sm::DispImage& exp = model.back().post;
        const sm::DispImage& got = res.frames[f];
        for (int y = 0; y < height; ++y)
          for (int x = 0; x < width; ++x)
            if (exp.at(x, y) != got.at(x, y)) {
              if (mismatches++ == 0)
                first_mismatch = fmt::format("frame {} x {} y {}: expected 0x{:04x} got 0x{:04x}", f, x, y,
                                             exp.at(x, y), got.at(x, y));
            }
        const std::vector<uint32_t> want = sm::object_packet(model.back().objects, false);
        if (f < res.object_packets.size() && res.object_packets[f].words != want) {
          if (mismatches++ == 0) first_mismatch = fmt::format("frame {}: object packet differs", f);
        }
      }
      if (res.object_packets.size() < in.frames.size() && mismatches++ == 0)
        first_mismatch = fmt::format("{} object packets for {} frames", res.object_packets.size(), in.frames.size());
    }

    // ---- figures ----
    const auto& s0 = res.stats.front();
    const uint64_t frame_cycles = s0.last_out_cycle - s0.sof_in_cycle + 1;
    const uint64_t latency = s0.first_out_cycle - s0.sof_in_cycle;
    const int line_period = width + (continuous ? 0 : hblank);
    uint64_t period = 0;
    if (res.stats.size() >= 2)
      period = res.stats.back().last_out_cycle - res.stats[res.stats.size() - 2].last_out_cycle;
    const uint64_t pixels = static_cast<uint64_t>(width) * height;
    // The IP needs one clock per pixel in steady state; its own rate bounds the clock.
    const uint64_t ip_cycles_per_frame = std::max<uint64_t>(pixels, continuous ? period : pixels);
    const double min_clock_30 = 30.0 * static_cast<double>(ip_cycles_per_frame);
    const double camera_clock = timing.clock_hz(width, height);
    const uint64_t camera_period = continuous ? pixels : static_cast<uint64_t>(width + hblank) * (height + vblank);
    const bool fps_ok = res.input_stall_cycles == 0 && (period == 0 || period <= camera_period);

    rep["input"] = in.name;
    rep["config"] = {{"max_width", hw.max_width},
                     {"max_height", hw.max_height},
                     {"disp", hw.disp},
                     {"census", hw.census},
                     {"sw", hw.sw},
                     {"rect_radius", hw.rect_radius},
                     {"width", width},
                     {"height", height}};
    rep["timing"] = {{"continuous", continuous},
                     {"hblank", continuous ? 0 : hblank},
                     {"vblank_lines", continuous ? 0 : vblank},
                     {"camera_pixel_clock_hz", camera_clock}};
    rep["frames"] = in.frames.size();
    rep["cycles_per_frame_sof_to_last_pixel"] = frame_cycles;
    rep["steady_state_frame_period_cycles"] = period;
    rep["latency_cycles"] = latency;
    rep["latency_lines"] = static_cast<double>(latency) / line_period;
    rep["input_stall_cycles"] = res.input_stall_cycles;
    rep["min_clock_hz_for_30fps"] = min_clock_30;
    rep["fps_at_clock"] = {{"clock_mhz", clock_mhz},
                           {"fps", clock_mhz * 1e6 / static_cast<double>(ip_cycles_per_frame)}};
    rep["meets_30fps_at_camera_clock"] = fps_ok;
    rep["framing_ok"] = res.framing_error.empty();
    if (!res.framing_error.empty()) rep["framing_error"] = res.framing_error;
    rep["bit_exact"] = no_check ? json(nullptr) : json(mismatches == 0);
    rep["mismatches"] = mismatches;
    if (mismatches) rep["first_mismatch"] = first_mismatch;
    rep["sim_wall_seconds"] = wall;
    rep["sim_frames_per_second"] = in.frames.size() / wall;
    rep["sim_cycles_per_second"] = res.cycles / wall;
    if (!in.gt.empty())
      rep["bad1_percent"] = sm::tools::bad1(sm::tools::disp_to_float(res.frames.back()), in.gt, in.mask).bad_pct();
    // Synthesis figures: the given report (it must be valid), else the one `synth_paper`
    // / `synth_small` built for this configuration, else the one committed in docs/synth.
    const bool synth_given = !synth_json.empty();
    if (!synth_given) {
      for (const char* cand : {SM_SYNTH_JSON, SM_SYNTH_JSON_DOCS})
        if (fs::exists(cand)) {
          synth_json = cand;
          break;
        }
    }
    if (!synth_json.empty()) {
      std::ifstream sj(synth_json);
      json s = json::parse(sj, nullptr, false);
      if (s.is_discarded() || !s.contains("total")) {
        if (synth_given) throw std::runtime_error(fmt::format("{}: not a synthesis report", synth_json));
        fmt::print(stderr, "note: {} is not a synthesis report, ignored\n", synth_json);
      } else {
        rep["synthesis"] = s["total"];
        rep["synthesis_report"] = synth_json;
      }
    }

    // ---- outputs ----
    fs::create_directories(out_dir);
    const cv::Mat disp_f = sm::tools::disp_to_float(res.frames.back());
    sm::tools::write_image_atomic(out_dir + "/disparity.png", sm::tools::disp_to_grey(disp_f, hw.disp));
    const cv::Mat colour = sm::tools::disp_to_colour(disp_f, hw.disp);
    sm::tools::write_image_atomic(out_dir + "/disparity_color.png", colour);
    {
      // Panel: left, right / rectified left, rectified right / disparity, objects.
      const sm::PipelineResult m = sm::run_pipeline(in.frames.back().first, in.frames.back().second, hw, regs, false);
      auto bgr = [](const sm::Image8& im) {
        cv::Mat c;
        cv::cvtColor(sm::tools::to_mat(im), c, cv::COLOR_GRAY2BGR);
        return c;
      };
      cv::Mat objects = colour.clone();
      for (const auto& o : m.objects.objects)
        cv::rectangle(objects, cv::Point(o.x0, o.y0), cv::Point(o.x1, o.y1), cv::Scalar(255, 255, 255), 1);
      cv::Mat row1, row2, row3, panel;
      cv::hconcat(bgr(in.frames.back().first), bgr(in.frames.back().second), row1);
      cv::hconcat(bgr(m.rl), bgr(m.rr), row2);
      cv::hconcat(colour, objects, row3);
      cv::vconcat(std::vector<cv::Mat>{row1, row2, row3}, panel);
      sm::tools::write_image_atomic(out_dir + "/panel.png", panel);
    }
    sm::tools::write_text_atomic(out_dir + "/report.json", rep.dump(2) + "\n");

    // ---- report ----
    fmt::print("stereo_sim: {} frame(s) of {}x{}, DISP {}, census {}x{}, SW {}x{}\n", in.frames.size(), width, height,
               hw.disp, hw.census, hw.census, hw.sw, hw.sw);
    fmt::print("  cycles per frame (sof in -> last pixel out): {}  (W*H = {}, + {} latency)\n", frame_cycles, pixels,
               frame_cycles - pixels);
    if (period) fmt::print("  steady-state frame period: {} cycles\n", period);
    fmt::print("  latency: {} cycles = {:.2f} lines\n", latency, static_cast<double>(latency) / line_period);
    fmt::print("  input stalls: {} cycles\n", res.input_stall_cycles);
    fmt::print("  minimum clock for 30 frames/s: {:.3f} MHz; at {} MHz: {:.1f} frames/s\n", min_clock_30 / 1e6,
               clock_mhz, clock_mhz * 1e6 / static_cast<double>(ip_cycles_per_frame));
    fmt::print("  30 frames/s at the camera clock ({:.3f} MHz): {}\n", camera_clock / 1e6, fps_ok ? "yes" : "NO");
    fmt::print("  framing: {}\n", res.framing_error.empty() ? "ok" : res.framing_error);
    if (!no_check)
      fmt::print("  bit-exact vs model: {}{}\n", mismatches == 0 ? "yes" : "NO, ",
                 mismatches == 0 ? "" : fmt::format("{} mismatches, first: {}", mismatches, first_mismatch));
    if (rep.contains("bad1_percent"))
      fmt::print("  bad-1.0 vs ground truth: {:.2f} %\n", rep["bad1_percent"].get<double>());
    if (rep.contains("synthesis")) {
      const json& t = rep["synthesis"];
      fmt::print("  synthesis: {} LUTs ({} LUT-RAM, {} SRL), {} FFs, {} RAMB36, {} DSP, {} LUT levels  [{}]\n",
                 t.value("luts", 0), t.value("lutram", 0), t.value("srl", 0), t.value("ffs", 0), t.value("bram36", 0.0),
                 t.value("dsp", 0), t.value("lut_levels", 0), rep["synthesis_report"].get<std::string>());
    }
    fmt::print("  simulation: {:.2f} s wall, {:.2f} frames/s, {:.0f} cycles/s\n", wall, in.frames.size() / wall,
               res.cycles / wall);
    fmt::print("  outputs in {}/\n", out_dir);
    return (mismatches == 0 && res.framing_error.empty()) ? 0 : 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stereo_sim: error: {}\n", e.what());
    return 2;
  }
}
