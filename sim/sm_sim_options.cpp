// stereo_sim's command line (sm_sim_options.hpp).
#include "sm_sim_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_reg_options.hpp"
#include "sm_sim_shards.hpp"
#include "sm_wave_names.hpp"
#include "lower_case.hpp"

namespace fs = std::filesystem;

namespace sm::simapp {

namespace {

// A user's scope in Verilog form: "TOP.sm_top.u_dp", also "sm_top.u_dp" or "u_dp".
std::string full_scope(const std::string& s) {
  if (s == "TOP" || s.rfind("TOP.", 0) == 0) return s;
  if (s == "sm_top" || s.rfind("sm_top.", 0) == 0) return "TOP." + s;
  return "TOP.sm_top." + s;
}

struct SizeOptions {
  CLI::Option* width = nullptr;
  CLI::Option* height = nullptr;
};

SizeOptions add_input_options(CLI::App& app, const HwConfig& hw, SimOptions& o) {
  auto* left = app.add_option("--left", o.left, "left image (with --right)");
  auto* right = app.add_option("--right", o.right, "right image (with --left)");
  auto* seq = app.add_option("--sequence", o.seq_dir, "folder of left*/right* image pairs, sorted by name");
  auto* video = app.add_option("--video", o.video, "side-by-side stereo video (left half, right half)");
  auto* scene = app.add_option("--scene", o.scene_dir,
                               "scene folder: left.png right.png, optionally gt.png with scale.txt (ground truth "
                               "= gt.png / scale) and nonocc.png; without gt.png the run is not scored")
                    ->capture_default_str();
  // One input: a pair, a sequence, a video or a scene.
  left->needs(right);
  right->needs(left);
  for (auto* a : {left, right}) a->excludes(seq)->excludes(video)->excludes(scene);
  seq->excludes(video)->excludes(scene);
  video->excludes(scene);
  app.add_option("--frames", o.frames,
                 "frames to stream: at most this many of a sequence or video (default: all of them); a pair or "
                 "scene is repeated (default 2)")
      ->check(tools::int_in(1, 100000));
  // The active size's real limits: MIN_WIDTH..MAX_WIDTH and MIN_HEIGHT..MAX_HEIGHT (docs/registers.md).
  SizeOptions s;
  s.width = app.add_option("--width", o.width, "active width")
                ->check(tools::int_in(hw.min_width(), hw.max_width))
                ->capture_default_str();
  s.height = app.add_option("--height", o.height, "active height")
                 ->check(tools::int_in(hw.min_height(), hw.max_height))
                 ->capture_default_str();
  return s;
}

// Returns the value register options (--occ, --gain-l, ...), which must live as long as `app`.
std::shared_ptr<const tools::RegOptions> add_register_options(CLI::App& app, const HwConfig& hw, SimOptions& o) {
  app.add_option("--regs", o.regs_file,
                 "register file (JSON, the keys of stereo_model --regs: every run-time register, 'calib'), "
                 "written before the first frame");
  app.add_option("--regs-at", o.regs_at,
                 "FRAME=FILE: from input frame FRAME on, these registers change (on top of the frame before); "
                 "written over AXI4-Lite while frame FRAME-1 streams (repeatable)");
  app.add_option("--calib", o.calib, "calibration JSON from sm_calibrate (written over AXI4-Lite)");
  // every other value register (--occ, --occ-edge, --gain-l, ...), written before the first frame
  return std::make_shared<const tools::RegOptions>(app, Regs::defaults(hw), hw,
                                                   std::set<std::string>{"WIDTH", "HEIGHT"},
                                                   std::map<std::string, std::string>{{"FILTER_ENABLE", "--filters"}});
}

void add_camera_options(CLI::App& app, const HwConfig& hw, SimOptions& o) {
  auto* continuous = app.add_flag("--continuous", o.continuous, "no blanking: one pixel every clock");
  // The blanking does not apply to a continuous stream: refused with --continuous.
  app.add_option("--hblank", o.hblank, "camera horizontal blanking (cycles)")
      ->check(tools::int_in(0, 65535))
      ->capture_default_str()
      ->excludes(continuous);
  app.add_option("--vblank", o.vblank, "camera vertical blanking (lines)")
      ->check(tools::int_in(0, 4095))
      ->capture_default_str()
      ->excludes(continuous);
  app.add_option("--pixel-clock", o.pixel_clock, "camera pixel clock in Hz (default: 30 frames/s)")
      ->check(tools::finite_in(1.0e3, 1.0e10));
  app.add_option("--clock-mhz", o.clock_mhz, "clock for the frames/s figure")
      ->check(tools::finite_in(1.0e-3, 1.0e5))
      ->capture_default_str();
  app.add_option("--core-mhz", o.core_mhz,
                 fmt::format("core clock (aclk) in MHz; camera pixels arrive on it at the camera's cadence "
                             "(default: the slowest the camera allows, {} x its pixel clock; at 1 clock per "
                             "pixel aclk is the pixel clock itself); given, it asks for the 30 frames/s "
                             "check: exit 3 when the verdict is NO",
                             hw.clocks_per_beat()))
      ->check(tools::finite_in(1.0e-3, 1.0e5));
}

void add_wave_options(CLI::App& app, const ModelInfo& info, SimOptions& o) {
  auto* o_wave = app.add_option("--wave,--vcd", o.wave_path,
                                fmt::format("dump a wave window to this file, .vcd{} (e.g. waves/top.vcd); traced: {}",
                                            info.wave_fst ? " or .fst" : "", info.traced));
  app.add_option("--wave-scope", o.wave_scopes,
                 "dump only this scope's signals, e.g. TOP.sm_top.u_dp (also sm_top.u_dp or u_dp; repeatable)")
      ->needs(o_wave);
  app.add_option("--wave-depth", o.wave_depth,
                 "levels below each --wave-scope: 1 = its own signals, 2 = and its children's, 0 = all")
      ->check(tools::int_in(0, 1000))
      ->capture_default_str();
  app.add_flag("--wave-scopes", o.wave_list_scopes, "list the scopes this simulator traces and exit");
  app.add_option("--wave-list", o.wave_list, "list the signals of a .vcd/.fst file (GTKWave's names) and exit");
  app.add_option("--vcd-frame", o.vcd_frame, "VCD window: input frame")
      ->needs(o_wave)
      ->check(tools::int_in(0, 100000))
      ->capture_default_str();
  app.add_option("--vcd-line", o.vcd_line, "VCD window: input line")
      ->needs(o_wave)
      ->check(tools::int_in(0, info.hw.max_height - 1))
      ->capture_default_str();
  app.add_option("--vcd-lines", o.vcd_lines, "VCD window: line periods to dump")
      ->needs(o_wave)
      ->check(tools::int_in(1, 1000000))
      ->capture_default_str();
  app.add_option("--vcd-cycles", o.vcd_cycles, "VCD window: cycles to dump (overrides lines)")
      ->needs(o_wave)
      ->check(tools::int_in(0, 1000000000000LL));
}

void add_output_options(CLI::App& app, SimOptions& o) {
  app.add_option("--out", o.out_dir, "output folder (disparity, panel, report.json)")->capture_default_str();
  app.add_option("--disp-file", o.disp_file,
                 "lossless disparity of the last frame: .pfm = float PFM (+inf = invalid, Middlebury), .png = "
                 "16-bit PNG of disparity x 16 (0 = invalid, KITTI style) (default: <out>/disparity.pfm)");
  app.add_flag("--disp-each-frame", o.disp_each, "also write every frame's disparity as <disp-file stem>_NNN<ext>");
  o.depth.add(app);  // the last frame's; the camera is --calib's, else the --scene folder's calib.json
  app.add_option("--synth-json", o.synth_json,
                 "synthesis report JSON (default: build/synth, else docs/synth, for this configuration)");
  app.add_flag("--no-check", o.no_check, "skip the reference-model comparison");
  app.add_flag("-q,--quiet", o.quiet, "no progress output");
  // A deliberate fault for the tests: every scheduled change is written one frame late.
  app.add_flag("--debug-late-regs", o.late_regs, "")->group("");
}

}  // namespace

std::optional<int> parse_sim_options(int argc, char** argv, const ModelInfo& info, SimOptions& opt) {
  auto app = std::make_shared<CLI::App>("Cycle-accurate simulation of the census stereo IP (Verilator)");
  opt.scene_dir = info.default_scene;
  opt.width = info.hw.max_width;
  opt.height = info.hw.max_height;
  const SizeOptions size = add_input_options(*app, info.hw, opt);
  const auto reg_opts = add_register_options(*app, info.hw, opt);
  add_camera_options(*app, info.hw, opt);
  add_wave_options(*app, info, opt);
  add_output_options(*app, opt);
  add_shard_options(*app, opt.shard);
  opt.shard.argv.assign(argv, argv + argc);
  app->footer(
      "Exit codes: 0 the run is bit-exact, well framed and every register write on time (and, with --core-mhz, "
      "30 frames/s is met); 1 it is not; 2 bad input or an output that cannot be written (one line 'stereo_sim: "
      "error: ...', nothing written); 3 --core-mhz given and the 30 frames/s verdict is NO (docs/robustness.md).");
  try {
    app->parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app->exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app->exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "stereo_sim: error: {}\n", e.what());
    return 2;
  }
  opt.width_given = size.width->count() > 0;
  opt.height_given = size.height->count() > 0;
  opt.core_mhz_given = app->count("--core-mhz") > 0;
  // reg_opts reads its options' counts: the app stays alive with it
  opt.apply_reg_options = [app, reg_opts](const HwConfig& hw, Regs& r) { reg_opts->apply(hw, r); };
  if (opt.disp_file.empty()) opt.disp_file = opt.out_dir + "/disparity.pfm";
  if (const auto rc = check_shard_options(opt)) return rc;
  if (opt.wave_depth > 0 && opt.wave_scopes.empty()) {
    fmt::print(stderr, "stereo_sim: error: --wave-depth needs --wave-scope\n");
    return 2;
  }
  return std::nullopt;
}

void check_wave_options(const ModelInfo& info, SimOptions& opt) {
  // Verilator's dumpvars() needs the fixed trace runtime of the wave builds (sim/sim.cmake).
  if (!opt.wave_scopes.empty() && !info.wave_build)
    fail(
        fmt::format("--wave-scope needs a wave build (stereo_sim_wave, stereo_sim_small_wave); this simulator "
                    "traces {}",
                    info.traced));
  for (auto& s : opt.wave_scopes) s = full_scope(s);
  opt.wave_fmt = info.wave_vcd ? "vcd" : "fst";
  if (opt.wave_path.empty()) return;
  const std::string& path = opt.wave_path;
  opt.wave_fmt = wave_extension(path);
  if (opt.wave_fmt != "vcd" && opt.wave_fmt != "fst")
    fail(fmt::format("--wave {}: the file name must end in .vcd or .fst", path));
  if ((opt.wave_fmt == "vcd" && !info.wave_vcd) || (opt.wave_fmt == "fst" && !info.wave_fst))
    fail(fmt::format("--wave {}: this simulator writes {} only ({})", path,
                     info.wave_vcd && info.wave_fst ? ".vcd and .fst" : (info.wave_vcd ? ".vcd" : ".fst"),
                     info.wave_build ? "built with SM_WAVE_FORMATS without it" : info.traced));
  // No window from an earlier run is left to look like this run's when this one fails.
  std::error_code ec;
  fs::remove(path, ec);
}

void check_disp_file_option(const SimOptions& opt) {
  const std::string ext = lower_extension(opt.disp_file);
  if (ext != ".pfm" && ext != ".png") fail(fmt::format("{}: --disp-file must end in .pfm or .png", opt.disp_file));
}

}  // namespace sm::simapp
