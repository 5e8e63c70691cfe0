// sm_evaluate: accuracy (bad-1.0), the streak measure and single-thread run time of the
// reference model (its output after every post-processing step) and of OpenCV's StereoBM,
// StereoSGBM and StereoBinarySGBM (opencv_contrib "stereo"; filtered and dense variants,
// by default each at the scene's own disparity range) on a stereo dataset in the
// ../shared/datasets layout, or on synthetic scenes from the sm_scene generator. Invalid
// outputs count as bad (dense comparison); beside bad-1.0 every output gets bad-0.5, bad-2.0,
// the mean absolute error and bad-1.0 over its valid pixels and its density, and the model's
// sub-pixel outputs (model_subpix: dense, model_checked: the validity rules; model/outword.hpp)
// the sparsification of their confidence; model_host is the checked output as a host that
// holds the frame can improve it (toolio/sm_host_speckle.hpp). Disparity files made by
// another program (--results: <scene>.pfm or <scene>.png) are scored the same way.
// docs/evaluation.md.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <optional>
#include <opencv2/core.hpp>
#include <opencv2/stereo.hpp>
#include <regex>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_host_speckle.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_pictures.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_regs_json.hpp"
#include "calib_file.hpp"
#include "configs.hpp"
#include "toolio/sm_scenegen.hpp"
#include "outword.hpp"
#include "pipeline.hpp"
#include "smooth.hpp"
#include "sm_defs.hpp"

namespace {

namespace fs = std::filesystem;
using sm::tools::ToolError;
using json = nlohmann::json;

// What a method's run gives: one disparity map (CV_32F, < 0 invalid) per name in `outputs`
// and, where it has one, the output's confidence (CV_8U; empty otherwise).
struct MethodOut {
  std::vector<cv::Mat> disp, conf;
};
MethodOut maps(std::vector<cv::Mat> disp) {
  const size_t n = disp.size();
  return {std::move(disp), std::vector<cv::Mat>(n)};
}

// One method: run() gives one or more disparity maps, one per name in `outputs` (the model:
// the DP output, each post-processing step and the sub-pixel dense and checked outputs;
// everything else: one).
struct Method {
  std::string name;                                                   // --methods name
  std::vector<std::string> outputs;                                   // table columns / JSON keys
  std::function<MethodOut(const sm::tools::Scene&, int levels)> run;  // one map per output
  bool peer = false;  // an OpenCV matcher: runs at --peer-levels (else at --levels)
  bool timed = true;  // false: read from a file, no run time
};

// OpenCV matchers produce 16x fixed point with values below minDisparity (0) invalid.
cv::Mat from_fixed16(const cv::Mat& d16) {
  cv::Mat f;
  d16.convertTo(f, CV_32F, 1.0 / 16);
  f.setTo(-1.0f, d16 < 0);
  return f;
}

int round16(int levels) { return (levels + 15) / 16 * 16; }

// --threads: the model's thread count (set once before any method runs; same output for any).
int model_threads = 1;
std::string model_config = "paper";     // --config: the model's configuration (sm::named_config)
std::optional<int> model_speckle_rows;  // --speckle-rows: SPECKLE_ROWS in place of the configuration's

// A scene's disparity file in the --results folder: <scene>.pfm or <scene>.png.
std::string result_file(const std::string& dir, const std::string& scene) {
  const fs::path pfm = fs::path(dir) / (scene + ".pfm"), png = fs::path(dir) / (scene + ".png");
  std::error_code ec;
  const bool has_pfm = fs::exists(pfm, ec), has_png = fs::exists(png, ec);
  if (has_pfm && has_png) throw ToolError(fmt::format("{}: both {}.pfm and {}.png exist; keep one", dir, scene, scene));
  if (!has_pfm && !has_png) throw ToolError(fmt::format("{}: no {}.pfm or {}.png", dir, scene, scene));
  return (has_pfm ? pfm : png).string();
}

// Peer settings: the ones behind the team's fair-peer figures (../shared/notes,
// docs/evaluation.md "Streaks and fair peers"); `dense` switches off every filter that
// invalidates pixels (uniqueness, speckle, left-right check; StereoBM also its texture
// threshold).
cv::Mat run_bm(const sm::tools::Scene& s, int nd, bool dense) {
  auto bm = cv::StereoBM::create(nd, 15);
  if (dense) {
    bm->setUniquenessRatio(0);
    bm->setTextureThreshold(0);
    bm->setSpeckleWindowSize(0);
    bm->setDisp12MaxDiff(-1);
  }
  cv::Mat d;
  bm->compute(s.left, s.right, d);
  return from_fixed16(d);
}

cv::Mat run_sgbm(const sm::tools::Scene& s, int nd, bool dense, int mode) {
  const int bs = 5;  // block 5, P1 = 8*25, P2 = 32*25 (OpenCV's stereo_match sample)
  auto sg = dense ? cv::StereoSGBM::create(0, nd, bs, 8 * bs * bs, 32 * bs * bs, -1, 0, 0, 0, 0, mode)
                  : cv::StereoSGBM::create(0, nd, bs, 8 * bs * bs, 32 * bs * bs, 1, 63, 10, 100, 32, mode);
  cv::Mat d;
  sg->compute(s.left, s.right, d);
  return from_fixed16(d);
}

cv::Mat run_binsgbm(const sm::tools::Scene& s, int nd, bool dense) {
  auto sg = dense ? cv::stereo::StereoBinarySGBM::create(0, nd, 9, 100, 1000, -1, 0, 0, 0, 0)
                  : cv::stereo::StereoBinarySGBM::create(0, nd, 9, 100, 1000, 1, 0, 5, 100, 32);
  sg->setBinaryKernelType(cv::stereo::CV_MODIFIED_CENSUS_TRANSFORM);
  sg->setSubPixelInterpolationMethod(cv::stereo::CV_SIMETRICV_INTERPOLATION);
  cv::Mat d;
  sg->compute(s.left, s.right, d);
  return from_fixed16(d);
}

// The model's output words (model/outword.hpp, smoothed: model/smooth.hpp) in its two modes: dense (every pixel valid,
// the DP's fill, the Q.4 fraction) with its confidence, and checked (the registers' rules: res.out, which run_pipeline
// made at the registers regs come from); then the host's recipe on the same evidence (model_host).
void add_output_modes(const sm::PipelineResult& res, int levels, const sm::OutputRegs& regs, MethodOut& o) {
  const sm::OutImage dense = sm::stream_words(res.evidence, res.post, levels, sm::dense_mode(regs));
  o.disp.push_back(sm::tools::out_to_float(dense));
  o.conf.push_back(sm::tools::out_to_conf(dense));
  o.disp.push_back(sm::tools::out_to_float(res.out));
  o.conf.emplace_back();
  // model_host: the host recipe of docs/evaluation.md "Speckles" -- the IP with the
  // left-right and agreement rules and the smoothing off, then the host's speckle check.
  sm::OutputRegs host = regs;
  host.lr_en = host.agree_en = host.smooth_en = 0;
  cv::Mat host_disp = sm::tools::out_to_float(sm::stream_words(res.evidence, res.post, levels, host));
  sm::tools::host_speckle(host_disp, sm::tools::kHostSpeckleSize, sm::tools::kHostSpeckleDiff);
  o.disp.push_back(host_disp);
  o.conf.emplace_back();
}

// The scene folder's calib.json (sm_scene writes one; a raw, unrectified pair needs it),
// when it is for the scene's size: its rectifier grids for the model. Nothing for a scene
// without one (the Middlebury scenes are rectified). Throws when it does not fit `hw`.
std::optional<sm::CalibFile> scene_calib(const sm::tools::Scene& s, const sm::HwConfig& hw) {
  if (s.dir.empty()) return std::nullopt;
  const std::string path = (fs::path(s.dir) / "calib.json").string();
  if (!fs::exists(path)) return std::nullopt;
  sm::CalibFile c = sm::load_calib(path);
  if (c.width != s.left.cols || c.height != s.left.rows) return std::nullopt;
  sm::check_calib_fits(path, c, hw);
  return c;
}

std::vector<Method> all_methods(int occ, bool occ_given, const std::string& regs_file, const std::string& results_dir,
                                double results_scale) {
  std::vector<Method> m;
  // The model with every post-processing filter enabled (the default registers), scored
  // after each step: the DP output, F0 (band filter), F0+F1 (5x1 vertical median), F0+F1+F2
  // (3x3), F0+F1+F2+F3 (5x3) = the model's output.
  m.push_back(
      {"model",
       {"model_dp", "model_f0", "model_f1", "model_f1f2", "model", "model_subpix", "model_checked", "model_host"},
       [occ, occ_given, regs_file](const sm::tools::Scene& s, int levels) {
         sm::HwConfig hw = sm::named_config(model_config);  // its sizes and levels: the scene's
         hw.disp = levels;
         hw.max_width = s.left.cols;
         hw.max_height = s.left.rows;
         if (model_speckle_rows) hw.speckle_rows = *model_speckle_rows;
         sm::Regs regs = sm::Regs::defaults(hw);  // (with the stage: its speckle mode)
         regs.occ = static_cast<uint8_t>(occ);
         regs.filter_enable = 15;
         if (!regs_file.empty()) {
           // --regs: registers and compile-time parameters on top of the defaults;
           // the sizes stay the scene's, --occ (when given) wins over the file.
           sm::tools::apply_regs_json(regs_file, hw, regs);
           hw.disp = levels;
           hw.max_width = s.left.cols;
           hw.max_height = s.left.rows;
           regs.width = hw.max_width;
           regs.height = hw.max_height;
           if (occ_given) regs.occ = static_cast<uint8_t>(occ);
           hw.validate();
         }
         if (const auto c = scene_calib(s, hw)) {  // a raw pair: rectified by the IP's grids
           regs.grid_l = c->left;
           regs.grid_r = c->right;
           regs.rect_enable = true;
         }
         const auto res = sm::run_pipeline(sm::tools::to_image8(s.left), sm::tools::to_image8(s.right), hw, regs, false,
                                           model_threads);
         if (res.post_steps.size() != 4 || res.post_steps.back() != res.post)
           throw std::logic_error("model: expected four post-processing steps ending in the output");
         MethodOut o = maps({sm::tools::disp_to_float(res.dp), sm::tools::disp_to_float(res.post_steps[0]),
                             sm::tools::disp_to_float(res.post_steps[1]), sm::tools::disp_to_float(res.post_steps[2]),
                             sm::tools::disp_to_float(res.post)});
         add_output_modes(res, hw.disp, sm::output_regs(regs), o);
         return o;
       }});
  using Scene = sm::tools::Scene;
  auto peer = [&m](const std::string& name, std::function<cv::Mat(const Scene&, int)> f) {
    m.push_back({name, {name}, [f](const Scene& s, int nd) { return maps({f(s, nd)}); }, true});
  };
  peer("bm", [](const Scene& s, int nd) { return run_bm(s, nd, false); });
  peer("bm-dense", [](const Scene& s, int nd) { return run_bm(s, nd, true); });
  peer("sgbm", [](const Scene& s, int nd) { return run_sgbm(s, nd, false, cv::StereoSGBM::MODE_SGBM); });
  peer("sgbm-dense", [](const Scene& s, int nd) { return run_sgbm(s, nd, true, cv::StereoSGBM::MODE_SGBM); });
  peer("sgbm-hh", [](const Scene& s, int nd) { return run_sgbm(s, nd, false, cv::StereoSGBM::MODE_HH); });
  peer("sgbm-hh-dense", [](const Scene& s, int nd) { return run_sgbm(s, nd, true, cv::StereoSGBM::MODE_HH); });
  peer("binsgbm", [](const Scene& s, int nd) { return run_binsgbm(s, nd, false); });
  peer("binsgbm-dense", [](const Scene& s, int nd) { return run_binsgbm(s, nd, true); });
  // Another program's disparities, read from --results (PFM: +inf invalid; PNG: value /
  // --results-scale, 0 invalid), scored exactly like the methods above.
  m.push_back({"results",
               {"results"},
               [results_dir, results_scale](const Scene& s, int) {
                 if (results_dir.empty()) throw ToolError("--methods results: no --results folder given");
                 const std::string f = result_file(results_dir, s.name);
                 cv::Mat d = sm::tools::read_disparity_file(f, results_scale);
                 if (d.size() != s.left.size())
                   throw ToolError(fmt::format("{}: size {}x{} differs from the scene's {}x{}", f, d.cols, d.rows,
                                               s.left.cols, s.left.rows));
                 return maps({d});
               },
               false,
               false});
  return m;
}

// Accuracy of one output (docs/evaluation.md, "Sub-pixel, validity and confidence"): the
// metrics of toolio/sm_metrics.hpp and, when the output has a confidence, its sparsification.
void score_accuracy(const cv::Mat& est, const cv::Mat& conf, const sm::tools::Scene& sc, sm::tools::DispMetrics& acc,
                    sm::tools::Sparsification& sparse, bool& has_conf) {
  acc = sm::tools::disp_metrics(est, sc.gt, sc.nonocc);
  has_conf = !conf.empty();
  if (has_conf) sparse = sm::tools::sparsification(est, conf, sc.gt, sc.nonocc, 100);
}

json accuracy_json(const sm::tools::DispMetrics& a, const sm::tools::Sparsification& sp, bool has_conf) {
  json j = {{"bad05_pct", a.pct(a.bad05)}, {"bad1_pct", a.pct(a.bad1)},  {"bad2_pct", a.pct(a.bad2)},
            {"mae_valid", a.mae()},        {"density_pct", a.density()}, {"bad1_valid_pct", a.bad1_of_valid()}};
  if (has_conf)
    j["sparsification"] = {{"kept_step", 0.01},
                           {"curve", sp.curve},
                           {"oracle", sp.oracle},
                           {"auc", sp.auc},
                           {"oracle_auc", sp.oracle_auc}};
  return j;
}

// The accuracy tables (one column per output, a mean row): bad-0.5/1.0/2.0 with invalid
// pixels counted bad, the mean absolute error and bad-1.0 over the valid pixels, the
// density, and for the outputs with a confidence the sparsification AUC against the oracle.
template <class TableFn, class AllCols, class ConfCols>
void print_accuracy_tables(const TableFn& table, const AllCols& all_cols, const ConfCols& conf_cols) {
  auto pct = [&](const char* title, long sm::tools::DispMetrics::*field) {
    table(
        title, false, [field](const auto& c) { return fmt::format("{:.2f}", c.acc.pct(c.acc.*field)); },
        [field](const auto& c) { return c.acc.pct(c.acc.*field); }, "{:.2f}", all_cols);
  };
  pct("bad-0.5 % (invalid = bad)", &sm::tools::DispMetrics::bad05);
  pct("bad-2.0 % (invalid = bad)", &sm::tools::DispMetrics::bad2);
  table(
      "mean absolute error (px) over the valid pixels", false,
      [](const auto& c) { return fmt::format("{:.3f}", c.acc.mae()); }, [](const auto& c) { return c.acc.mae(); },
      "{:.3f}", all_cols);
  table(
      "density % (valid share of the evaluated pixels)", false,
      [](const auto& c) { return fmt::format("{:.2f}", c.acc.density()); },
      [](const auto& c) { return c.acc.density(); }, "{:.2f}", all_cols);
  table(
      "bad-1.0 % over the valid pixels", false,
      [](const auto& c) { return fmt::format("{:.2f}", c.acc.bad1_of_valid()); },
      [](const auto& c) { return c.acc.bad1_of_valid(); }, "{:.2f}", all_cols);
  table(
      "confidence: area under the sparsification curve (bad-1.0 % of the kept pixels, 1 % steps), oracle in "
      "brackets",
      false, [](const auto& c) { return fmt::format("{:.3f} ({:.3f})", c.sparse.auc, c.sparse.oracle_auc); },
      [](const auto& c) { return c.sparse.auc; }, "{:.3f}", conf_cols);
  table(
      "confidence: oracle AUC", false, [](const auto& c) { return fmt::format("{:.3f}", c.sparse.oracle_auc); },
      [](const auto& c) { return c.sparse.oracle_auc; }, "{:.3f}", conf_cols);
}

// A markdown table (header, rows of cells), printed with padded columns under a title.
struct Table {
  std::vector<std::string> head;
  std::vector<std::vector<std::string>> rows;
  void print(const std::string& title) const {
    std::vector<size_t> w(head.size(), 3);
    for (size_t c = 0; c < head.size(); ++c) {
      w[c] = std::max(w[c], head[c].size());
      for (const auto& r : rows) w[c] = std::max(w[c], r[c].size());
    }
    auto line = [&](const std::vector<std::string>& cells) {
      std::string l = "|";
      for (size_t c = 0; c < cells.size(); ++c)
        l += c == 0 ? fmt::format(" {:<{}} |", cells[c], w[c]) : fmt::format(" {:>{}} |", cells[c], w[c]);
      return l;
    };
    fmt::print("\n{}\n\n{}\n", title, line(head));
    std::string sep = "|";
    for (size_t c = 0; c < head.size(); ++c) sep += std::string(w[c] + 2, '-') + "|";
    fmt::print("{}\n", sep);
    for (const auto& r : rows) fmt::print("{}\n", line(r));
  }
};

// --synthetic-size WxH: two integers 16..4095 (the scene generator's sizes), nothing else.
std::pair<int, int> synthetic_size(const std::string& text) {
  static const std::regex re("([0-9]{1,4})x([0-9]{1,4})");
  std::smatch m;
  if (std::regex_match(text, m, re)) {
    const int w = std::stoi(m[1]), h = std::stoi(m[2]);
    if (w >= 16 && w <= 4095 && h >= 16 && h <= 4095) return {w, h};
  }
  throw ToolError(fmt::format("--synthetic-size {}: expected WxH, each 16..4095", text));
}

// The synthetic scenes' size and levels, checked before any work in the options' terms
// (the model needs levels / 2 + 3 columns; the generator's own limits, as it says them).
void check_synthetic_fits(const std::string& text, int w, int h, int levels) {
  if (w < levels / 2 + 3)
    throw sm::tools::UsageError(fmt::format("--synthetic-size {}: {} levels need at least {} columns (levels / 2 + 3)",
                                            text, levels, levels / 2 + 3));
  sm::tools::SceneParams p;
  p.width = w;
  p.height = h;
  p.levels = levels;
  p.seed = 1;
  try {
    sm::tools::render_scene(p);
  } catch (const std::invalid_argument& e) {
    throw sm::tools::UsageError(fmt::format("--synthetic-size {} at {} levels: {}", text, levels, e.what()));
  }
}

// The files named on the command line, checked before any work: the register file reads
// and applies (its keys and ranges), the outputs can be written (the --disp-images folder
// is created when the outputs are committed).
void check_files(const std::string& regs_file, int levels, const std::string& json_path, const std::string& disp_dir) {
  if (!regs_file.empty()) {
    sm::tools::check_input_file(regs_file);
    sm::HwConfig hw;  // the largest scene (the sizes are the scene's), --levels where given
    hw.max_width = sm::defs::limit("MAX_WIDTH").max;
    hw.max_height = sm::defs::limit("MAX_HEIGHT").max;
    if (levels) hw.disp = levels;
    sm::Regs r = sm::Regs::defaults(hw);
    sm::tools::apply_regs_json(regs_file, hw, r);
  }
  sm::tools::check_outputs({{"--json", json_path}});
  if (!disp_dir.empty()) sm::tools::check_output_folder("--disp-images", disp_dir, {{"--json", json_path}});
}

int run(int argc, char** argv) {
  std::string dataset, json_path, disp_dir;
  std::vector<std::string> scenes_opt,
      methods_opt{"model",         "bm",      "bm-dense",     "sgbm", "sgbm-dense", "sgbm-hh",
                  "sgbm-hh-dense", "binsgbm", "binsgbm-dense"};
  std::string synth_size = fmt::format("{}x{}", sm::HwConfig{}.max_width, sm::HwConfig{}.max_height), results_dir,
              regs_file;
  double results_scale = 16;
  int levels = sm::HwConfig{}.disp, peer_levels = 0, synthetic = 0, occ = sm::Regs{}.occ;
  std::vector<int> streak_rows{1, 5};
  bool quiet = false;
  CLI::App app{"bad-1.0, streak measure and run time of the model and OpenCV matchers on a stereo dataset"};
  auto* o_dataset = app.add_option(
      "dataset", dataset, "dataset folder (scene subfolders with left/right/gt.png, scale.txt) or one scene folder");
  app.add_option("--scenes", scenes_opt, "comma-separated scene names (default: all)")->delimiter(',');
  app.add_option("--json", json_path, "write the results as JSON");
  app.add_option("--levels", levels, "model: disparity levels (0: per scene, from scale.txt, made even)")
      ->capture_default_str();
  app.add_option("--peer-levels", peer_levels,
                 "OpenCV matchers: numDisparities (multiple of 16; 0: per scene, scale.txt levels rounded up to 16)")
      ->capture_default_str();
  app.add_option("--streak-rows", streak_rows,
                 "streak measure: report streaks up to these many rows thick (comma-separated, each 1..8)")
      ->delimiter(',')
      ->check(sm::tools::int_in(1, 8))
      ->capture_default_str();
  app.add_option("--disp-images", disp_dir,
                 "write <scene>_<method>.png colour disparity maps (over the ground truth's range, with a colour "
                 "bar), <scene>_<method>_errors.png error maps with their legend and <scene>_gt.png here");
  app.add_option("--methods", methods_opt,
                 "comma-separated subset of model,bm,bm-dense,sgbm,sgbm-dense,sgbm-hh,sgbm-hh-dense,binsgbm,"
                 "binsgbm-dense,results")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--results", results_dir,
                 "score another program's disparities: folder of <scene>.pfm (+inf = invalid) or <scene>.png "
                 "(value / --results-scale, 0 = invalid); adds the method 'results'");
  app.add_option("--results-scale", results_scale, "PNG results: disparity = value / scale (KITTI: 256)")
      ->check(sm::tools::finite_in(1e-3, 1e6))
      ->capture_default_str();
  app.add_option("--synthetic", synthetic, "evaluate N synthetic scenes (sm_scene seeds 1..N) instead of a dataset")
      ->check(sm::tools::int_in(1, 1000))
      ->excludes(o_dataset);
  app.add_option("--synthetic-size", synth_size, "WxH of the synthetic scenes")->capture_default_str();
  app.add_option("--occ", occ, "model: DP occlusion penalty register")
      ->check(sm::tools::int_in(0, 255))
      ->capture_default_str();
  app.add_option("--regs", regs_file,
                 "model: register file (stereo_model --regs format: registers and compile-time parameters such as "
                 "sw_table, filter_enable, band_k, cost_shift) applied on top of the defaults; sizes and levels stay "
                 "the scene's, --occ wins when given");
  app.add_option("--config", model_config,
                 "model: the configuration whose parameters and register resets it models (sizes and levels "
                 "stay the scene's; zynq: its speckle stage and speckle mode)")
      ->check(CLI::IsMember(sm::config_names()))
      ->capture_default_str();
  app.add_option("--speckle-rows", model_speckle_rows,
                 "model: the speckle stage's rows, SPECKLE_ROWS, in place of the configuration's (0: none, as "
                 "at the paper configuration; 32: the zynq configuration's); with the stage the registers "
                 "reset into its speckle mode: SPECKLE_EN 1, LR_EN 0, AGREE_EN 0")
      ->check(sm::tools::int_in(sm::defs::limit("SPECKLE_ROWS").min, sm::defs::limit("SPECKLE_ROWS").max));
  app.add_option("--threads", model_threads, "model: threads, 1..256 (same output for any count; OpenCV stays on one)")
      ->check(sm::tools::int_in(1, 256))
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "no progress lines");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::check_levels("--levels", levels, true);
  check_files(regs_file, levels, json_path, disp_dir);
  sm::tools::quiet_opencv();
  cv::setNumThreads(1);
  if (peer_levels != 0 && (peer_levels < 16 || peer_levels > 256 || peer_levels % 16))
    throw sm::tools::UsageError(fmt::format("--peer-levels {}: must be 0 or a multiple of 16, 16..256", peer_levels));
  if (streak_rows.empty()) throw ToolError("--streak-rows: empty");
  if (!results_dir.empty() && !fs::is_directory(results_dir))
    throw ToolError(fmt::format("{}: not a directory", results_dir));
  std::vector<Method> methods;
  {
    const bool occ_given = app.count("--occ") > 0;
    const auto all = all_methods(occ, occ_given, regs_file, results_dir, results_scale);
    auto names_opt = methods_opt;
    names_opt.erase(std::remove(names_opt.begin(), names_opt.end(), ""), names_opt.end());
    if (!results_dir.empty() && std::find(names_opt.begin(), names_opt.end(), "results") == names_opt.end())
      names_opt.push_back("results");
    for (const auto& n : names_opt) {
      auto it = std::find_if(all.begin(), all.end(), [&](const Method& m) { return m.name == n; });
      if (it == all.end()) throw ToolError(fmt::format("--methods: unknown method '{}'", n));
      if (n == "results" && results_dir.empty()) throw ToolError("--methods results: no --results folder given");
      if (std::any_of(methods.begin(), methods.end(), [&](const Method& m) { return m.name == n; }))
        throw ToolError(fmt::format("--methods: '{}' given twice", n));
      methods.push_back(*it);
    }
    if (methods.empty()) throw ToolError("--methods: empty");
  }
  std::vector<std::string> outputs;  // every table column, in method order
  for (const auto& m : methods) outputs.insert(outputs.end(), m.outputs.begin(), m.outputs.end());

  // Scene list: dataset folders, or synthetic scenes rendered in memory.
  std::vector<std::function<sm::tools::Scene()>> loaders;
  std::vector<std::string> names;
  if (synthetic > 0) {
    const auto [w, h] = synthetic_size(synth_size);
    const int lv = levels ? levels : 128;
    check_synthetic_fits(synth_size, w, h, lv);
    for (int seed = 1; seed <= synthetic; ++seed) {
      names.push_back(fmt::format("synthetic{}", seed));
      loaders.push_back([=]() {
        sm::tools::SceneParams p;
        p.width = w;
        p.height = h;
        p.levels = lv;
        p.seed = static_cast<uint64_t>(seed);
        const auto s = sm::tools::render_scene(p);
        sm::tools::Scene sc;
        sc.name = fmt::format("synthetic{}", seed);
        sc.left = s.left;
        sc.right = s.right;
        sc.gt = s.gt.clone();
        sc.gt.setTo(1e-3f, sc.gt <= 0);  // every synthetic pixel is known
        sc.nonocc = s.nonocc;
        sc.scale = sm::tools::kGtScale;
        sc.levels = lv;
        return sc;
      });
    }
  } else {
    if (dataset.empty()) throw ToolError("no dataset folder given (or use --synthetic N)");
    auto dirs = sm::tools::list_scenes(dataset);
    auto wanted = scenes_opt;
    wanted.erase(std::remove(wanted.begin(), wanted.end(), ""), wanted.end());
    for (const auto& wn : wanted)
      if (std::none_of(dirs.begin(), dirs.end(), [&](const std::string& d) { return fs::path(d).filename() == wn; }))
        throw ToolError(fmt::format("{}: no scene '{}'", dataset, wn));
    for (const auto& d : dirs) {
      const std::string n = fs::path(d).filename().string();
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), n) == wanted.end()) continue;
      names.push_back(n.empty() ? d : n);
      loaders.push_back([d]() { return sm::tools::load_scene(d); });
    }
    if (loaders.empty())
      throw ToolError(fmt::format("{}: no scenes (folders with left.png right.png gt.png scale.txt)", dataset));
  }
  // Every output under a temporary name, renamed into place once the whole run succeeded.
  sm::tools::OutputSet outs;

  json jout;
  jout["dataset"] = synthetic > 0 ? fmt::format("synthetic x{} ({})", synthetic, synth_size) : dataset;
  if (!results_dir.empty()) jout["results"] = {{"dir", results_dir}, {"png_scale", results_scale}};
  jout["metric"] = "bad-1.0 %: |d - gt| > 1 over known gt pixels (nonocc mask where present); invalid = bad";
  jout["streak_metric"] =
      "streak %: share of smooth pixels (evaluated, both vertical neighbours evaluated with gt within 1) whose "
      "estimate d is valid and bad and lies between two valid rows, at most max_rows rows apart, that differ from d "
      "by more than 1, with every row between evaluated and gt within 1 (toolio/sm_io.hpp, streaks)";
  jout["peer_levels"] = peer_levels ? json(peer_levels) : json("scene");
  jout["threads"] = model_threads;  // the model's; OpenCV runs on one
  jout["model_config"] = model_config;
  if (model_speckle_rows) jout["model_speckle_rows"] = *model_speckle_rows;
  jout["scenes"] = json::array();
  struct Cell {
    sm::tools::BadStats bad;
    sm::tools::DispMetrics acc;        // bad-0.5/1.0/2.0, MAE, density
    sm::tools::Sparsification sparse;  // outputs with a confidence only
    bool has_conf = false;
    std::vector<sm::tools::StreakStats> streak;  // one per --streak-rows
    double ms = -1;                              // < 0: not timed
  };
  struct Row {
    std::string name, size;
    int levels = 0, peer_levels = 0;
    std::vector<Cell> cells;  // one per output
  };
  std::vector<Row> rows;
  const size_t total_steps = loaders.size() * methods.size();
  size_t step = 0;
  for (size_t i = 0; i < loaders.size(); ++i) {
    sm::tools::Scene sc = loaders[i]();
    sc.name = names[i];  // --results files are looked up by this name
    const int lv = levels ? levels : std::min(254, (sc.levels + 1) / 2 * 2);
    const int plv = peer_levels ? peer_levels : round16(std::max(1, sc.levels));
    Row row{names[i], fmt::format("{}x{}", sc.left.cols, sc.left.rows), lv, plv, {}};
    cv::Mat gt_f = sc.gt.clone();  // the pictures' colour range: the ground truth's
    gt_f.setTo(-1.0f, sc.gt <= 0);
    json js = {{"name", names[i]},       {"width", sc.left.cols},
               {"height", sc.left.rows}, {"levels", lv},
               {"peer_levels", plv},     {"scene_levels", sc.levels},
               {"gt_scale", sc.scale},   {"nonocc_mask", !sc.nonocc.empty()}};
    // the scene's calib.json rectifies the model's input (the OpenCV matchers get the raw pair)
    const bool has_calib = !sc.dir.empty() && fs::exists(fs::path(sc.dir) / "calib.json");
    js["calib"] = has_calib ? json((fs::path(sc.dir) / "calib.json").string()) : json(nullptr);
    if (has_calib && !quiet) fmt::print(stderr, "{}: the model rectifies with the scene's calib.json\n", names[i]);
    for (const auto& m : methods) {
      ++step;
      const int mlv = m.peer ? plv : lv;
      if (!quiet)
        fmt::print(stderr, "[{}/{}] {} ({}, {} levels): {} ...\n", step, total_steps, names[i], row.size, mlv, m.name);
      const auto t0 = std::chrono::steady_clock::now();
      const MethodOut mo = m.run(sc, mlv);
      const std::vector<cv::Mat>& est = mo.disp;
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (est.size() != m.outputs.size()) throw std::logic_error(m.name + ": wrong number of outputs");
      for (size_t k = 0; k < est.size(); ++k) {
        const std::string& out = m.outputs[k];
        Cell c;
        c.bad = sm::tools::bad1(est[k], sc.gt, sc.nonocc);
        c.ms = m.timed && out == m.name ? ms : -1.0;
        score_accuracy(est[k], mo.conf[k], sc, c.acc, c.sparse, c.has_conf);
        json jst = json::array();
        for (int t : streak_rows) {
          c.streak.push_back(sm::tools::streaks(est[k], sc.gt, sc.nonocc, t));
          jst.push_back({{"max_rows", t}, {"pct", c.streak.back().streak_pct()}, {"pixels", c.streak.back().streak}});
        }
        js["methods"][out] = {{"bad1_pct", c.bad.bad_pct()},
                              {"evaluated", c.bad.evaluated},
                              {"bad", c.bad.bad},
                              {"invalid", c.bad.invalid},
                              {"smooth", c.streak[0].smooth},
                              {"streak", jst},
                              {"levels", mlv},
                              {"accuracy", accuracy_json(c.acc, c.sparse, c.has_conf)},
                              {"ms", c.ms >= 0 ? json(c.ms) : json(nullptr)}};
        row.cells.push_back(c);
        if (!disp_dir.empty()) {
          const fs::path stem = fs::path(disp_dir) / fmt::format("{}_{}", names[i], out);
          outs.write(
              stem.string() + ".png",
              [&](const std::string& t) {
                sm::tools::write_image_atomic(t, sm::tools::disparity_picture(est[k], sm::tools::data_range(gt_f)));
              },
              true);
          outs.write(
              stem.string() + "_errors.png",
              [&](const std::string& t) {
                sm::tools::write_image_atomic(t, sm::tools::error_map_picture(est[k], sc.gt, sc.nonocc));
              },
              true);
        }
      }
    }
    if (!disp_dir.empty())
      outs.write((fs::path(disp_dir) / fmt::format("{}_gt.png", names[i])).string(),
                 [&](const std::string& t) {
                   sm::tools::write_image_atomic(t, sm::tools::disparity_picture(gt_f, sm::tools::data_range(gt_f)));
                 },
                 true);
    jout["scenes"].push_back(js);
    rows.push_back(row);
  }

  // Tables (markdown): bad-1.0 % with the invalid share, streak %, ms per frame; one column
  // per output, a mean row over the scenes.
  const double n = static_cast<double>(rows.size());
  auto mean_of = [&](size_t k, const std::function<double(const Cell&)>& f) {
    double sum = 0;
    for (const auto& r : rows) sum += f(r.cells[k]);
    return sum / n;
  };
  // mean_fmt: the mean row's format; keep(k): whether output k gets a column.
  auto table = [&](const std::string& title, bool with_smooth, const std::function<std::string(const Cell&)>& cell,
                   const std::function<double(const Cell&)>& value, const char* mean_fmt,
                   const std::function<bool(size_t)>& keep) {
    Table t;
    t.head = {"scene", "size", "levels", "peer levels"};
    if (with_smooth) t.head.push_back("smooth px");
    for (size_t k = 0; k < outputs.size(); ++k)
      if (keep(k)) t.head.push_back(outputs[k]);
    for (const auto& r : rows) {
      std::vector<std::string> cells{r.name, r.size, std::to_string(r.levels), std::to_string(r.peer_levels)};
      if (with_smooth) cells.push_back(std::to_string(r.cells.at(0).streak.at(0).smooth));
      for (size_t k = 0; k < outputs.size(); ++k)
        if (keep(k)) cells.push_back(cell(r.cells[k]));
      t.rows.push_back(cells);
    }
    std::vector<std::string> mean{"mean", "", "", ""};
    if (with_smooth) mean.push_back("");
    for (size_t k = 0; k < outputs.size(); ++k)
      if (keep(k)) mean.push_back(fmt::format(mean_fmt, mean_of(k, value)));
    t.rows.push_back(mean);
    t.print(title);
  };
  const auto all_cols = [](size_t) { return true; };
  table(
      "bad-1.0 % (invalid % in brackets)", false,
      [](const Cell& c) {
        return fmt::format("{:.2f} ({:.1f})", c.bad.bad_pct(),
                           c.bad.evaluated ? 100.0 * c.bad.invalid / c.bad.evaluated : 0.0);
      },
      [](const Cell& c) { return c.bad.bad_pct(); }, "{:.2f}", all_cols);
  for (size_t i = 0; i < streak_rows.size(); ++i)
    table(
        fmt::format("streak % (streaks up to {} row{} thick, of the smooth pixels)", streak_rows[i],
                    streak_rows[i] == 1 ? "" : "s"),
        true, [i](const Cell& c) { return fmt::format("{:.2f}", c.streak[i].streak_pct()); },
        [i](const Cell& c) { return c.streak[i].streak_pct(); }, "{:.2f}", all_cols);
  print_accuracy_tables(table, all_cols, [&](size_t k) { return !rows.empty() && rows[0].cells[k].has_conf; });
  table(
      "ms per frame (OpenCV on one thread, the model on --threads; the model's steps come from one run)", false,
      [](const Cell& c) { return fmt::format("{:.0f}", c.ms); }, [](const Cell& c) { return c.ms; }, "{:.0f}",
      [&](size_t k) { return !rows.empty() && rows[0].cells[k].ms >= 0; });
  for (size_t k = 0; k < outputs.size(); ++k) {
    const bool timed = !rows.empty() && rows[0].cells[k].ms >= 0;
    json jst = json::array();
    for (size_t i = 0; i < streak_rows.size(); ++i)
      jst.push_back(
          {{"max_rows", streak_rows[i]}, {"pct", mean_of(k, [i](const Cell& c) { return c.streak[i].streak_pct(); })}});
    jout["mean"][outputs[k]] = {{"bad1_pct", mean_of(k, [](const Cell& c) { return c.bad.bad_pct(); })},
                                {"bad05_pct", mean_of(k, [](const Cell& c) { return c.acc.pct(c.acc.bad05); })},
                                {"bad2_pct", mean_of(k, [](const Cell& c) { return c.acc.pct(c.acc.bad2); })},
                                {"mae_valid", mean_of(k, [](const Cell& c) { return c.acc.mae(); })},
                                {"density_pct", mean_of(k, [](const Cell& c) { return c.acc.density(); })},
                                {"bad1_valid_pct", mean_of(k, [](const Cell& c) { return c.acc.bad1_of_valid(); })},
                                {"streak", jst},
                                {"ms", timed ? json(mean_of(k, [](const Cell& c) { return c.ms; })) : json(nullptr)}};
  }
  if (!json_path.empty())
    outs.write(json_path, [&](const std::string& t) { sm::tools::write_text_atomic(t, jout.dump(2) + "\n"); });
  outs.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_evaluate", run, argc, argv); }
