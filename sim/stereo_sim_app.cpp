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
// (stereo_sim_app.hpp).
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <tuple>
#include <unistd.h>

#include "calib_file.hpp"
#include "pipeline.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_objects_json.hpp"
#include "toolio/sm_reg_options.hpp"
#include "toolio/sm_regs_json.hpp"
#include "sm_host.hpp"
#include "sm_regmap.hpp"
#include "sm_regs_io.hpp"
#include "sm_sim.hpp"
#include "sm_wave_names.hpp"
#include "stereo_sim_app.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct Input {
  std::vector<std::pair<sm::Image8, sm::Image8>> frames;
  cv::Mat gt;    // CV_32F disparity, 0 = unknown (empty when none)
  cv::Mat mask;  // 8-bit evaluation mask (empty: all known gt)
  std::string name;
  std::string gt_note;  // how the ground truth was resized (empty: at its own size)
  double gt_scale = 1;  // disparity factor applied to the ground truth
};

[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

// A user's scope in Verilog form: "TOP.sm_top.u_dp", also "sm_top.u_dp" or "u_dp".
std::string full_scope(const std::string& s) {
  if (s == "TOP" || s.rfind("TOP.", 0) == 0) return s;
  if (s == "sm_top" || s.rfind("sm_top.", 0) == 0) return "TOP." + s;
  return "TOP.sm_top." + s;
}

sm::Image8 to_size(const cv::Mat& grey, int w, int h, bool* resized) {
  cv::Mat g = grey;
  if (g.cols != w || g.rows != h) {
    cv::resize(grey, g, cv::Size(w, h), 0, 0, cv::INTER_AREA);
    *resized = true;
  }
  return sm::tools::to_image8(g);
}

// A register file on top of `r` (frame `what`): the compile-time keys must be this
// simulator's, the active size may only be set where `size_ok`, a calibration is applied.
// Returns whether the file had a calibration.
bool apply_regs_file(const std::string& path, const sm::HwConfig& hw, sm::Regs& r, bool size_ok) {
  sm::HwConfig h = hw;
  const int w0 = r.width, h0 = r.height;
  const sm::tools::RegsFile rf = sm::tools::apply_regs_json(path, h, r);
  const std::vector<std::tuple<const char*, int, int>> hw_keys = {{"max_width", h.max_width, hw.max_width},
                                                                  {"max_height", h.max_height, hw.max_height},
                                                                  {"disp", h.disp, hw.disp},
                                                                  {"census", h.census, hw.census},
                                                                  {"sw", h.sw, hw.sw},
                                                                  {"rect_radius", h.rect_radius, hw.rect_radius},
                                                                  {"cost_shift", h.cost_shift, hw.cost_shift},
                                                                  {"max_objects", h.max_objects, hw.max_objects},
                                                                  {"label_slots", h.label_slots, hw.label_slots},
                                                                  {"band_k", h.band_k, hw.band_k}};
  for (const auto& [k, got, want] : hw_keys)
    if (got != want) fail(fmt::format("{}: '{}' = {}, but this simulator is built with {}", path, k, got, want));
  if (!size_ok && (r.width != w0 || r.height != h0))
    fail(fmt::format("{}: '{}' = {}: the active size ({}x{}) cannot change within a run", path,
                     r.width != w0 ? "width" : "height", r.width != w0 ? r.width : r.height, w0, h0));
  if (!rf.calib.empty()) {
    try {
      sm::apply_calib(sm::load_calib(rf.calib), r);
    } catch (const std::exception& e) {
      fail(fmt::format("{}: 'calib' {}: {}", path, rf.calib, e.what()));
    }
  }
  return !rf.calib.empty();
}

// The register values of a frame, by the register file's key names.
json regs_json(const sm::Regs& r, int grid_bank) {
  json j;
  for (const sm::RegWord& w : sm::register_words(r)) {
    std::string k = w.name;
    std::transform(k.begin(), k.end(), k.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    j[k] = (k == "offset_l" || k == "offset_r") ? json(static_cast<int32_t>(w.value)) : json(w.value);
  }
  j["grid_bank"] = grid_bank;
  return j;
}

json object_json(const sm::ObjectPacket& p) {
  json j = {{"valid", p.valid}, {"count", p.objects.size()}, {"too_many", p.too_many}, {"table_full", p.table_full},
            {"lost", p.lost},   {"objects", json::array()}};
  for (const auto& o : p.objects) {
    json b = sm::tools::object_box_json(o);
    b.update(json{{"pixels", o.count}, {"sum_disp", o.sum_disp}, {"nearest_disp", o.max_disp}});
    j["objects"].push_back(b);
  }
  return j;
}

// A tile of the panel with its label in the top-left corner.
cv::Mat labelled(const cv::Mat& img, const std::string& label) {
  cv::Mat t = img.clone();
  const double scale = std::max(0.3, t.cols / 800.0);
  int base = 0;
  const cv::Size ts = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
  cv::rectangle(t, cv::Rect(0, 0, std::min(t.cols, ts.width + 4), std::min(t.rows, ts.height + base + 4)),
                cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(t, label, cv::Point(2, ts.height + 2), cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  return t;
}

// Error map against ground truth: green = within 1 px, red = off by more, magenta = no
// estimate, dark grey = not evaluated (unknown ground truth or occluded).
cv::Mat error_map(const cv::Mat& est, const cv::Mat& gt, const cv::Mat& mask) {
  cv::Mat m(gt.size(), CV_8UC3, cv::Scalar(40, 40, 40));
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      const float g = gt.at<float>(y, x);
      if (!(g > 0) || (!mask.empty() && mask.at<uint8_t>(y, x) == 0)) continue;
      const float e = est.at<float>(y, x);
      m.at<cv::Vec3b>(y, x) =
          e < 0 ? cv::Vec3b(255, 0, 255) : (std::fabs(e - g) > 1.0f ? cv::Vec3b(0, 0, 255) : cv::Vec3b(0, 160, 0));
    }
  return m;
}

// <stem>_<frame><ext> beside `path`.
std::string frame_path(const std::string& path, size_t f) {
  const fs::path p(path);
  return (p.parent_path() / fmt::format("{}_{:03d}{}", p.stem().string(), f, p.extension().string())).string();
}

}  // namespace

namespace sm::simapp {

int stereo_sim_main(int argc, char** argv, const ModelInfo& info, const RunFn& run_model,
                    const WaveNamesFn& wave_names) {
  CLI::App app{"Cycle-accurate simulation of the census stereo IP (Verilator)"};
  const sm::HwConfig& hw = info.hw;
  std::string left, right, seq_dir, video, scene_dir = info.default_scene, calib, out_dir = "out", synth_json, vcd_path;
  std::string regs_file, disp_file;
  std::vector<std::string> regs_at;
  int frames_n = 2, width = hw.max_width, height = hw.max_height;
  int hblank = 80, vblank = 22;
  bool continuous = false, quiet = false, no_check = false, disp_each = false, late_regs = false;
  double pixel_clock = 0, clock_mhz = 100.0, core_mhz = 0;
  int vcd_frame = 0, vcd_line = 0, vcd_lines = 4;
  uint64_t vcd_cycles = 0;
  app.add_option("--left", left, "left image (with --right)");
  app.add_option("--right", right, "right image");
  app.add_option("--sequence", seq_dir, "folder of left*/right* image pairs, sorted by name");
  app.add_option("--video", video, "side-by-side stereo video (left half, right half)");
  app.add_option("--scene", scene_dir, "scene folder (left.png right.png [gt.png scale.txt nonocc.png])")
      ->capture_default_str();
  app.add_option("--frames", frames_n, "frames to stream (a pair or scene is repeated)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  // The active size's real limits: MIN_WIDTH..MAX_WIDTH and 16..MAX_HEIGHT (docs/registers.md).
  auto* o_width = app.add_option("--width", width, "active width")
                      ->check(CLI::Range(hw.min_width(), hw.max_width))
                      ->capture_default_str();
  auto* o_height =
      app.add_option("--height", height, "active height")->check(CLI::Range(16, hw.max_height))->capture_default_str();
  app.add_option("--regs", regs_file,
                 "register file (JSON, the keys of stereo_model --regs: every run-time register, 'calib'), "
                 "written before the first frame");
  app.add_option("--regs-at", regs_at,
                 "FRAME=FILE: from input frame FRAME on, these registers change (on top of the frame before); "
                 "written over AXI4-Lite while frame FRAME-1 streams (repeatable)");
  app.add_option("--calib", calib, "calibration JSON from sm_calibrate (written over AXI4-Lite)");
  // every other value register (--occ, --occ-edge, --gain-l, ...), written before the first frame
  const sm::tools::RegOptions reg_opts(app, sm::Regs::defaults(hw), {"WIDTH", "HEIGHT"},
                                       {{"FILTER_ENABLE", "--filters"}});
  app.add_flag("--continuous", continuous, "no blanking: one pixel every clock");
  app.add_option("--hblank", hblank, "camera horizontal blanking (cycles)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app.add_option("--vblank", vblank, "camera vertical blanking (lines)")
      ->check(CLI::Range(0, 4095))
      ->capture_default_str();
  app.add_option("--pixel-clock", pixel_clock, "camera pixel clock in Hz (default: 30 frames/s)")
      ->check(CLI::Range(1.0e3, 1.0e10));
  app.add_option("--clock-mhz", clock_mhz, "clock for the frames/s figure")
      ->check(CLI::Range(1.0e-3, 1.0e5))
      ->capture_default_str();
  app.add_option("--core-mhz", core_mhz,
                 fmt::format("core clock (aclk) in MHz; camera pixels arrive on it at the camera's cadence "
                             "(default: the slowest the camera allows, {} x its pixel clock; at 1 clock per "
                             "pixel aclk is the pixel clock itself)",
                             hw.clocks_per_beat()))
      ->check(CLI::Range(1.0e-3, 1.0e5));
  std::vector<std::string> wave_scopes;
  int wave_depth = 0;
  bool wave_list_scopes = false;
  std::string wave_list;
  auto* o_wave = app.add_option("--wave,--vcd", vcd_path,
                                fmt::format("dump a wave window to this file, .vcd{} (e.g. waves/top.vcd); traced: {}",
                                            info.wave_fst ? " or .fst" : "", info.traced));
  app.add_option("--wave-scope", wave_scopes,
                 "dump only this scope's signals, e.g. TOP.sm_top.u_dp (also sm_top.u_dp or u_dp; repeatable)")
      ->needs(o_wave);
  app.add_option("--wave-depth", wave_depth,
                 "levels below each --wave-scope: 1 = its own signals, 2 = and its children's, 0 = all")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  app.add_flag("--wave-scopes", wave_list_scopes, "list the scopes this simulator traces and exit");
  app.add_option("--wave-list", wave_list, "list the signals of a .vcd/.fst file (GTKWave's names) and exit");
  app.add_option("--vcd-frame", vcd_frame, "VCD window: input frame")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  app.add_option("--vcd-line", vcd_line, "VCD window: input line")
      ->check(CLI::Range(0, hw.max_height - 1))
      ->capture_default_str();
  app.add_option("--vcd-lines", vcd_lines, "VCD window: line periods to dump")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  app.add_option("--vcd-cycles", vcd_cycles, "VCD window: cycles to dump (overrides lines)");
  app.add_option("--out", out_dir, "output folder (disparity, panel, report.json)")->capture_default_str();
  app.add_option("--disp-file", disp_file,
                 "lossless disparity of the last frame: .pfm = float PFM (+inf = invalid, Middlebury), .png = "
                 "16-bit PNG of disparity x 16 (0 = invalid, KITTI style) (default: <out>/disparity.pfm)");
  app.add_flag("--disp-each-frame", disp_each, "also write every frame's disparity as <disp-file stem>_NNN<ext>");
  app.add_option("--synth-json", synth_json,
                 "synthesis report JSON (default: build/synth, else docs/synth, for this configuration)");
  app.add_flag("--no-check", no_check, "skip the reference-model comparison");
  app.add_flag("-q,--quiet", quiet, "no progress output");
  // A deliberate fault for the tests: every scheduled change is written one frame late.
  app.add_flag("--debug-late-regs", late_regs, "")->group("");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "stereo_sim: error: {}\n", e.what());
    return 2;
  }

  if (wave_depth > 0 && wave_scopes.empty()) {
    fmt::print(stderr, "stereo_sim: error: --wave-depth needs --wave-scope\n");
    return 2;
  }
  try {
    if (!wave_list.empty()) {
      for (const auto& n : wave_names(wave_list)) fmt::print("{}\n", n);
      return 0;
    }
    // Verilator's dumpvars() needs the fixed trace runtime of the wave builds (sim/sim.cmake).
    if (!wave_scopes.empty() && !info.wave_build)
      fail(
          fmt::format("--wave-scope needs a wave build (stereo_sim_wave, stereo_sim_small_wave); this simulator "
                      "traces {}",
                      info.traced));
    for (auto& s : wave_scopes) s = full_scope(s);
    std::string wave_fmt = info.wave_vcd ? "vcd" : "fst";
    if (!vcd_path.empty()) {
      wave_fmt = sm::wave_extension(vcd_path);
      if (wave_fmt != "vcd" && wave_fmt != "fst")
        fail(fmt::format("--wave {}: the file name must end in .vcd or .fst", vcd_path));
      if ((wave_fmt == "vcd" && !info.wave_vcd) || (wave_fmt == "fst" && !info.wave_fst))
        fail(fmt::format("--wave {}: this simulator writes {} only ({})", vcd_path,
                         info.wave_vcd && info.wave_fst ? ".vcd and .fst" : (info.wave_vcd ? ".vcd" : ".fst"),
                         info.wave_build ? "built with SM_WAVE_FORMATS without it" : info.traced));
      // No window from an earlier run is left to look like this run's when this one fails.
      std::error_code ec;
      fs::remove(vcd_path, ec);
    }
    sm::tools::quiet_opencv();
    // ---- registers (before any input is read: a bad file simulates nothing) ----
    sm::Regs base = sm::Regs::defaults(hw);
    base.width = width;
    base.height = height;
    base.grid_l = sm::RectGrid::identity(width, height);
    base.grid_r = base.grid_l;
    if (!regs_file.empty()) {
      const int w0 = base.width, h0 = base.height;
      const bool file_calib = apply_regs_file(regs_file, hw, base, true);
      // --width / --height win over the file's active size.
      if (o_width->count()) base.width = width;
      if (o_height->count()) base.height = height;
      width = base.width;
      height = base.height;
      if (file_calib &&
          (base.grid_l.gw != sm::RectGrid::points_w(width) || base.grid_l.gh != sm::RectGrid::points_h(height)))
        fail(fmt::format("{}: its calibration is for another size than the active {}x{}", regs_file, width, height));
      if (!file_calib && (width != w0 || height != h0)) {
        base.grid_l = sm::RectGrid::identity(width, height);
        base.grid_r = base.grid_l;
      }
    }
    if (!calib.empty()) apply_calib(sm::load_calib(calib), base);
    reg_opts.apply(hw, base);  // a value out of range: a ToolError, one line like fail()
    // The schedule: FRAME=FILE entries, applied in frame order (command-line order within a frame).
    std::vector<std::pair<int, std::string>> sched;
    for (const std::string& e : regs_at) {
      const size_t eq = e.find('=');
      int f = -1;
      if (eq == std::string::npos || eq == 0 || eq + 1 == e.size() || !CLI::detail::lexical_cast(e.substr(0, eq), f) ||
          f < 0)
        fail(fmt::format("--regs-at {}: expected FRAME=FILE with FRAME >= 0", e));
      if (f >= frames_n) fail(fmt::format("--regs-at {}: frame {} is beyond the {} frame(s) streamed", e, f, frames_n));
      sched.emplace_back(f, e.substr(eq + 1));
    }
    std::stable_sort(sched.begin(), sched.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<sm::Regs> regs(static_cast<size_t>(frames_n), base);
    {
      size_t k = 0;
      for (int f = 0; f < frames_n; ++f) {
        if (f > 0) regs[f] = regs[f - 1];
        for (; k < sched.size() && sched[k].first == f; ++k) apply_regs_file(sched[k].second, hw, regs[f], false);
      }
    }
    for (size_t f = 0; f < regs.size(); ++f) {
      try {
        sm::validate_regs(regs[f], hw);
      } catch (const std::invalid_argument& e) {
        fail(fmt::format("registers of frame {}: {}", f, e.what()));
      }
    }
    if (!disp_file.empty()) {
      std::string ext = fs::path(disp_file).extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (ext != ".pfm" && ext != ".png") fail(fmt::format("{}: --disp-file must end in .pfm or .png", disp_file));
    }

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
        in.frames.emplace_back(to_size(l, width, height, &resized), to_size(r, width, height, &resized));
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
        in.frames.emplace_back(to_size(read_grey(ls[i].string()), width, height, &resized),
                               to_size(read_grey(rs[i].string()), width, height, &resized));
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
        in.frames.emplace_back(to_size(g(cv::Rect(0, 0, hw2, g.rows)), width, height, &resized),
                               to_size(g(cv::Rect(hw2, 0, hw2, g.rows)), width, height, &resized));
      }
      if (in.frames.empty()) fail(fmt::format("{}: no frames could be read", video));
      in.name = video;
    } else {
      const sm::tools::Scene sc = sm::tools::load_scene(scene_dir);
      const sm::Image8 l = to_size(sc.left, width, height, &resized);
      const sm::Image8 r = to_size(sc.right, width, height, &resized);
      for (int i = 0; i < frames_n; ++i) in.frames.emplace_back(l, r);
      if (!sc.gt.empty()) {
        if (sc.gt.cols == width && sc.gt.rows == height) {
          in.gt = sc.gt;
          in.mask = sc.nonocc;
        } else {
          // Resized scene: ground truth resized by nearest neighbour (no blending across
          // depth edges) and its disparities scaled by the width ratio.
          in.gt_scale = static_cast<double>(width) / sc.gt.cols;
          cv::resize(sc.gt, in.gt, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
          in.gt *= in.gt_scale;
          if (!sc.nonocc.empty()) cv::resize(sc.nonocc, in.mask, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
          in.gt_note = fmt::format("ground truth resized from {}x{} (nearest neighbour), disparities x {:.4f}",
                                   sc.gt.cols, sc.gt.rows, in.gt_scale);
        }
      }
      in.name = scene_dir;
    }
    if (resized && !quiet) fmt::print(stderr, "note: input resized to the active size {}x{}\n", width, height);
    const size_t nframes = in.frames.size();
    if (!sched.empty() && sched.back().first >= static_cast<int>(nframes))
      fail(fmt::format("--regs-at {}={}: the input has only {} frame(s)", sched.back().first, sched.back().second,
                       nframes));
    regs.resize(nframes);

    // ---- simulate ----
    if (!vcd_path.empty() && vcd_frame >= static_cast<int>(nframes))
      fail(fmt::format("--vcd-frame {}: the input has only {} frame(s)", vcd_frame, nframes));
    if (!vcd_path.empty() && vcd_line >= height)
      fail(fmt::format("--vcd-line {}: the active height is {}", vcd_line, height));
    std::vector<sm::FrameHostPlan> plan;
    const std::vector<sm::HostOp> host = sm::plan_register_schedule(regs, hw, late_regs, &plan);
    sm::CameraTiming timing;
    timing.continuous = continuous;
    timing.hblank = hblank;
    timing.vblank_lines = vblank;
    timing.pixel_clock_hz = pixel_clock;
    const int fold = hw.clocks_per_beat();  // clocks per pixel of the datapath
    timing.set_core(fold, core_mhz, width, height);
    if (core_mhz > 0 && timing.core_hz < timing.clock_hz(width, height))
      fail(fmt::format("--core-mhz {}: below the camera's pixel clock {:.3f} MHz", core_mhz,
                       timing.clock_hz(width, height) / 1e6));
    RunRequest req;
    req.frames = &in.frames;
    req.width = width;
    req.height = height;
    req.timing = timing;
    req.regs0 = &regs[0];
    req.host = &host;
    req.quiet = quiet;
    req.wave_fmt = wave_fmt;
    req.list_scopes = wave_list_scopes;
    req.wave_scopes = wave_scopes;
    req.wave_depth = wave_depth;
    req.window.path = vcd_path;
    req.window.frame = vcd_frame;
    req.window.line = vcd_line;
    req.window.lines = vcd_lines;
    req.window.cycles = vcd_cycles;
    for (const auto& sc : wave_scopes) req.window.scope.scopes.push_back({sc, wave_depth});
    RunResult run;
    const bool ran = run_model(req, run);
    if (!ran) return 0;  // --wave-scopes
    const sm::SimResult& res = run.res;
    const double wall = run.wall;
    // The status and error registers read back, field by field.
    json status;
    std::vector<std::string> status_lines;
    for (const auto& [ri, word] : run.status) {
      const auto& reg = sm::regmap::registers()[ri];
      const std::string name = reg.name;
      json j = {{"word", word}};
      std::string line = fmt::format("{:<13} 0x{:08x}", name, word);
      for (int i = 0; i < reg.num_fields; ++i) {
        const auto& fd = sm::regmap::fields()[static_cast<size_t>(reg.first_field + i)];
        const std::string fname = std::string(fd.name).substr(name.size() + 1);
        const uint32_t v = (word & fd.mask()) >> fd.lsb;
        j[fname] = v;
        line += fmt::format("  {} {}", fname, v);
      }
      status[name] = j;
      status_lines.push_back(line);
    }

    // ---- check against the model ----
    json rep;
    int mismatches = 0;
    std::string first_mismatch;
    std::vector<int> frame_mismatches(nframes, 0);
    std::vector<sm::PipelineResult> model;
    if (!no_check) {
      for (size_t f = 0; f < nframes; ++f) {
        model.push_back(sm::run_pipeline(in.frames[f].first, in.frames[f].second, hw, regs[f], false));
        const sm::DispImage& exp = model.back().post;
        const sm::DispImage& got = res.frames[f];
        for (int y = 0; y < height; ++y)
          for (int x = 0; x < width; ++x)
            if (exp.at(x, y) != got.at(x, y)) {
              ++frame_mismatches[f];
              if (mismatches++ == 0)
                first_mismatch = fmt::format("frame {} x {} y {}: expected 0x{:04x} got 0x{:04x}", f, x, y,
                                             exp.at(x, y), got.at(x, y));
            }
        const std::vector<uint32_t> want = sm::object_packet(model.back().objects, false);
        if (f < res.object_packets.size() && res.object_packets[f].words != want) {
          ++frame_mismatches[f];
          if (mismatches++ == 0) first_mismatch = fmt::format("frame {}: object packet differs", f);
        }
      }
      if (res.object_packets.size() < nframes && mismatches++ == 0)
        first_mismatch = fmt::format("{} object packets for {} frames", res.object_packets.size(), nframes);
    }

    // ---- figures ----
    const auto& s0 = res.stats.front();
    const uint64_t frame_cycles = s0.last_out_cycle - s0.sof_in_cycle + 1;
    const uint64_t input_cycles = s0.last_in_cycle - s0.sof_in_cycle + 1;
    const uint64_t tail_cycles = s0.last_out_cycle - s0.last_in_cycle;
    const uint64_t latency = s0.first_out_cycle - s0.sof_in_cycle;
    const double camera_clock = timing.clock_hz(width, height);
    const double aclk_per_cam = timing.aclk_per_camera_clock(width, height);
    const double core_hz = timing.aclk_hz(width, height);
    const double line_period = (width + (continuous ? 0 : hblank)) * aclk_per_cam;  // aclk cycles
    uint64_t period = 0;
    if (res.stats.size() >= 2)
      period = res.stats.back().last_out_cycle - res.stats[res.stats.size() - 2].last_out_cycle;
    const uint64_t pixels = static_cast<uint64_t>(width) * height;
    // The IP needs F = DISP / PU clocks per pixel in steady state; its own rate bounds the clock.
    const uint64_t ip_cycles_per_frame =
        std::max<uint64_t>(pixels * fold, continuous && timing.core_hz == 0 ? period : pixels * fold);
    const double min_clock_30 = 30.0 * static_cast<double>(ip_cycles_per_frame);
    // With this camera: its pixels must not arrive faster than one per F aclk cycles
    // (sm_seq's input FIFO rule, docs/streams.md "Pacing").
    const double min_core_camera = fold * camera_clock;
    const double camera_period =
        (continuous ? static_cast<double>(pixels) : static_cast<double>(width + hblank) * (height + vblank)) *
        aclk_per_cam;
    const uint64_t fifo_max = status.contains("IN_FIFO") ? status["IN_FIFO"]["LEVEL_MAX"].get<uint64_t>() : 0;
    const bool fps_ok =
        res.input_stall_cycles == 0 && (period == 0 || static_cast<double>(period) <= std::ceil(camera_period));

    rep["input"] = in.name;
    rep["config"] = {{"max_width", hw.max_width},
                     {"max_height", hw.max_height},
                     {"disp", hw.disp},
                     {"census", hw.census},
                     {"sw", hw.sw},
                     {"rect_radius", hw.rect_radius},
                     {"max_objects", hw.max_objects},
                     {"width", width},
                     {"height", height}};
    rep["config"]["pu"] = hw.levels_per_clock();
    rep["timing"] = {{"continuous", continuous},
                     {"hblank", continuous ? 0 : hblank},
                     {"vblank_lines", continuous ? 0 : vblank},
                     {"camera_pixel_clock_hz", camera_clock},
                     {"core_clock_hz", core_hz}};
    rep["clocks_per_pixel"] = fold;
    rep["min_core_clock_hz_this_camera"] = min_core_camera;
    rep["input_fifo_level_max"] = fifo_max;
    rep["frames"] = nframes;
    rep["cycles_per_frame_sof_to_last_pixel"] = frame_cycles;
    rep["input_cycles_per_frame"] = input_cycles;  // sof in -> last pixel in: W*H + camera blanking
    rep["camera_blanking_cycles_per_frame"] = input_cycles - std::min(input_cycles, pixels);
    rep["last_pixel_in_to_out_cycles"] = tail_cycles;
    rep["steady_state_frame_period_cycles"] = period;
    rep["latency_cycles"] = latency;
    rep["latency_lines"] = static_cast<double>(latency) / line_period;
    rep["input_stall_cycles"] = res.input_stall_cycles;
    rep["min_clock_hz_for_30fps"] = min_clock_30;
    rep["fps_at_clock"] = {{"clock_mhz", clock_mhz},
                           {"fps", clock_mhz * 1e6 / static_cast<double>(ip_cycles_per_frame)}};
    rep["meets_30fps_with_camera_at_core_clock"] = fps_ok;
    rep["framing_ok"] = res.framing_error.empty();
    if (!res.framing_error.empty()) rep["framing_error"] = res.framing_error;
    rep["bit_exact"] = no_check ? json(nullptr) : json(mismatches == 0);
    rep["mismatches"] = mismatches;
    if (mismatches) rep["first_mismatch"] = first_mismatch;
    rep["register_schedule"] = {
        {"files", json::array()}, {"axi_writes", res.host_writes}, {"ok", res.host_errors.empty()}};
    for (const auto& [f, file] : sched) rep["register_schedule"]["files"].push_back({{"frame", f}, {"file", file}});
    if (!res.host_errors.empty()) rep["register_schedule"]["errors"] = res.host_errors;
    // Per frame: its registers, what the host changed for it, the RTL's object packet.
    std::vector<sm::ObjectPacket> packets;
    rep["frame_results"] = json::array();
    for (size_t f = 0; f < nframes; ++f) {
      json fr = {{"frame", f}, {"registers", regs_json(regs[f], plan[f].grid_bank)}, {"changed", plan[f].changed}};
      if (f < res.object_packets.size()) {
        packets.push_back(sm::decode_object_packet(res.object_packets[f].words));
        fr["object_packet"] = object_json(packets.back());
      } else {
        fr["object_packet"] = nullptr;
      }
      if (!no_check) fr["bit_exact"] = frame_mismatches[f] == 0;
      rep["frame_results"].push_back(fr);
    }
    rep["status"] = status;
    rep["sim_wall_seconds"] = wall;
    rep["sim_frames_per_second"] = nframes / wall;
    rep["sim_cycles_per_second"] = res.cycles / wall;
    const cv::Mat disp_f = sm::tools::disp_to_float(res.frames.back());
    if (!in.gt.empty()) {
      rep["bad1_percent"] = sm::tools::bad1(disp_f, in.gt, in.mask).bad_pct();
      rep["ground_truth"] = {{"resized", !in.gt_note.empty()}, {"disparity_scale", in.gt_scale}};
      if (!in.gt_note.empty()) rep["ground_truth"]["note"] = in.gt_note;
    }
    // Synthesis figures: the given report (it must be valid), else the one `synth_paper`
    // / `synth_small` built for this configuration, else the one committed in docs/synth.
    const bool synth_given = !synth_json.empty();
    if (!synth_given) {
      for (const std::string& cand : {info.synth_json, info.synth_json_docs})
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
    sm::tools::write_image_atomic(out_dir + "/disparity.png", sm::tools::disp_to_grey(disp_f, hw.disp));
    const cv::Mat colour = sm::tools::disp_to_colour(disp_f, hw.disp);
    sm::tools::write_image_atomic(out_dir + "/disparity_color.png", colour);
    if (disp_file.empty()) disp_file = out_dir + "/disparity.pfm";
    sm::tools::write_disparity_file(disp_file, disp_f);
    if (disp_each)
      for (size_t f = 0; f < nframes; ++f)
        sm::tools::write_disparity_file(frame_path(disp_file, f), sm::tools::disp_to_float(res.frames[f]));
    rep["disparity_file"] = disp_file;
    {
      // Panel: left, right / rectified left, rectified right / disparity, objects (the
      // RTL's packet) / error map, ground truth when there is one. Last frame.
      const sm::PipelineResult m =
          no_check ? sm::run_pipeline(in.frames.back().first, in.frames.back().second, hw, regs.back(), false)
                   : model.back();
      auto bgr = [](const sm::Image8& im) {
        cv::Mat c;
        cv::cvtColor(sm::tools::to_mat(im), c, cv::COLOR_GRAY2BGR);
        return c;
      };
      cv::Mat objects = colour.clone();
      const std::vector<sm::Object>& boxes = packets.empty() ? m.objects.objects : packets.back().objects;
      for (const auto& o : boxes)
        cv::rectangle(objects, cv::Point(o.x0, o.y0), cv::Point(o.x1, o.y1), cv::Scalar(255, 255, 255), 1);
      std::vector<cv::Mat> rows(3);
      cv::hconcat(labelled(bgr(in.frames.back().first), "left"), labelled(bgr(in.frames.back().second), "right"),
                  rows[0]);
      cv::hconcat(labelled(bgr(m.rl), "rectified left"), labelled(bgr(m.rr), "rectified right"), rows[1]);
      cv::hconcat(labelled(colour, "disparity"), labelled(objects, fmt::format("objects ({})", boxes.size())), rows[2]);
      if (!in.gt.empty()) {
        cv::Mat gt_f = in.gt.clone();
        gt_f.setTo(-1.0f, in.gt <= 0);
        rows.emplace_back();
        cv::hconcat(labelled(error_map(disp_f, in.gt, in.mask),
                             fmt::format("error map (bad-1.0 {:.1f} %)", rep["bad1_percent"].get<double>())),
                    labelled(sm::tools::disp_to_colour(gt_f, hw.disp), "ground truth"), rows[3]);
      }
      cv::Mat panel;
      cv::vconcat(rows, panel);
      sm::tools::write_image_atomic(out_dir + "/panel.png", panel);
    }
    sm::tools::write_text_atomic(out_dir + "/report.json", rep.dump(2) + "\n");

    // ---- report ----
    fmt::print("stereo_sim: {} frame(s) of {}x{}, DISP {}, census {}x{}, SW {}x{}\n", nframes, width, height, hw.disp,
               hw.census, hw.census, hw.sw, hw.sw);
    fmt::print(
        "  cycles per frame (sof in -> last pixel out): {} = {} input (W*H = {} pixels + {} {}) + {} "
        "last pixel in -> out\n",
        frame_cycles, input_cycles, pixels, input_cycles - std::min(input_cycles, pixels),
        timing.core_hz > 0 ? "cycles between them: camera cadence and blanking" : "camera blanking", tail_cycles);
    if (period) fmt::print("  steady-state frame period: {} cycles\n", period);
    fmt::print("  latency (sof in -> first pixel out): {} cycles = {:.2f} lines\n", latency,
               static_cast<double>(latency) / line_period);
    fmt::print("  clocks per pixel: {} (DISP {} / PU {}); core clock {:.3f} MHz, camera pixel clock {:.3f} MHz\n", fold,
               hw.disp, hw.levels_per_clock(), core_hz / 1e6, camera_clock / 1e6);
    fmt::print("  input stalls: {} cycles; input FIFO high-water mark: {} pixels\n", res.input_stall_cycles, fifo_max);
    fmt::print(
        "  minimum core clock for 30 frames/s: {:.3f} MHz (F x W x H x 30); with this camera {:.3f} MHz (F x its "
        "pixel clock); at {} MHz: {:.1f} frames/s\n",
        min_clock_30 / 1e6, min_core_camera / 1e6, clock_mhz,
        clock_mhz * 1e6 / static_cast<double>(ip_cycles_per_frame));
    fmt::print("  30 frames/s with this camera at this core clock ({:.3f} MHz): {}\n", core_hz / 1e6,
               fps_ok ? "yes" : "NO");
    fmt::print("  framing: {}\n", res.framing_error.empty() ? "ok" : res.framing_error);
    if (!no_check)
      fmt::print("  bit-exact vs model: {}{}\n", mismatches == 0 ? "yes" : "NO, ",
                 mismatches == 0 ? "" : fmt::format("{} mismatches, first: {}", mismatches, first_mismatch));
    if (!sched.empty() || late_regs)
      fmt::print("  register schedule: {} file(s), {} AXI4-Lite writes while streaming{}{}\n", sched.size(),
                 res.host_writes, late_regs ? " (deliberately one frame late)" : "",
                 res.host_errors.empty() ? "" : "; " + res.host_errors.front());
    fmt::print("  objects (from m_axis_obj):\n");
    for (size_t f = 0; f < nframes; ++f) {
      std::string changed;
      for (const auto& c : plan[f].changed) changed += (changed.empty() ? "" : ",") + c;
      if (f >= packets.size()) {
        fmt::print("    frame {}: no packet\n", f);
        continue;
      }
      const sm::ObjectPacket& p = packets[f];
      fmt::print("    frame {}: {} object(s){}{}{}{}{}{}\n", f, p.objects.size(), p.too_many ? ", TOO-MANY" : "",
                 p.table_full ? ", TABLE-FULL" : "", p.lost ? ", LOST (a packet before was dropped)" : "",
                 p.valid ? "" : ", MALFORMED packet",
                 no_check || frame_mismatches[f] == 0 ? "" : ", differs from model",
                 changed.empty() ? "" : "  [changed: " + changed + "]");
      for (size_t i = 0; i < p.objects.size(); ++i) {
        const sm::Object& o = p.objects[i];
        fmt::print("      #{} x {}..{} y {}..{}  {} px  mean d {}  nearest d {}\n", i, o.x0, o.x1, o.y0, o.y1, o.count,
                   o.mean_disp, o.max_disp);
      }
    }
    fmt::print("  status read back over AXI4-Lite:\n");
    for (const auto& l : status_lines) fmt::print("    {}\n", l);
    if (rep.contains("bad1_percent"))
      fmt::print("  bad-1.0 vs ground truth: {:.2f} %{}\n", rep["bad1_percent"].get<double>(),
                 in.gt_note.empty() ? "" : " (" + in.gt_note + ")");
    if (rep.contains("synthesis")) {
      const json& t = rep["synthesis"];
      fmt::print("  synthesis: {} LUTs ({} LUT-RAM, {} SRL), {} FFs, {} RAMB36, {} DSP, {} LUT levels  [{}]\n",
                 t.value("luts", 0), t.value("lutram", 0), t.value("srl", 0), t.value("ffs", 0), t.value("bram36", 0.0),
                 t.value("dsp", 0), t.value("lut_levels", 0), rep["synthesis_report"].get<std::string>());
    }
    fmt::print("  simulation: {:.2f} s wall, {:.2f} frames/s, {:.0f} cycles/s\n", wall, nframes / wall,
               res.cycles / wall);
    fmt::print("  outputs in {}/ (lossless disparity: {})\n", out_dir, disp_file);
    return (mismatches == 0 && res.framing_error.empty() && res.host_errors.empty()) ? 0 : 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stereo_sim: error: {}\n", e.what());
    return 2;
  }
}

}  // namespace sm::simapp
