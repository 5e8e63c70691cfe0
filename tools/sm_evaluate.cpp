// sm_evaluate: accuracy (bad-1.0), the streak measure and single-thread run time of the
// reference model (its output after every post-processing step) and of OpenCV's StereoBM,
// StereoSGBM and StereoBinarySGBM (opencv_contrib "stereo"; filtered and dense variants,
// by default each at the scene's own disparity range) on a stereo dataset in the
// ../shared/datasets layout, or on synthetic scenes from the sm_scene generator. Invalid
// outputs count as bad (dense comparison). Disparity files made by another program
// (--results: <scene>.pfm or <scene>.png) are scored the same way. docs/evaluation.md.
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
#include <opencv2/core.hpp>
#include <opencv2/stereo.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "toolio/sm_io.hpp"
#include "toolio/sm_regs_json.hpp"
#include "toolio/sm_scenegen.hpp"
#include "pipeline.hpp"

namespace {

namespace fs = std::filesystem;
using sm::tools::ToolError;
using json = nlohmann::json;

// One method: run() gives one or more disparity maps (CV_32F, < 0 invalid), one per name in
// `outputs` (the model: the DP output and each post-processing step; everything else: one).
struct Method {
  std::string name;                                                              // --methods name
  std::vector<std::string> outputs;                                              // table columns / JSON keys
  std::function<std::vector<cv::Mat>(const sm::tools::Scene&, int levels)> run;  // one map per output
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

std::vector<Method> all_methods(int occ, bool occ_given, const std::string& regs_file, const std::string& results_dir,
                                double results_scale) {
  std::vector<Method> m;
  // The model with every post-processing filter enabled (the default registers), scored
  // after each step: the DP output, F0 (band filter), F0+F1 (5x1 vertical median), F0+F1+F2
  // (3x3), F0+F1+F2+F3 (5x3) = the model's output.
  m.push_back({"model",
               {"model_dp", "model_f0", "model_f1", "model_f1f2", "model"},
               [occ, occ_given, regs_file](const sm::tools::Scene& s, int levels) {
                 sm::HwConfig hw;  // paper defaults: CENSUS 15, SW 5
                 hw.disp = levels;
                 hw.max_width = s.left.cols;
                 hw.max_height = s.left.rows;
                 sm::Regs regs = sm::Regs::defaults(hw);
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
                 const auto res = sm::run_pipeline(sm::tools::to_image8(s.left), sm::tools::to_image8(s.right), hw,
                                                   regs, false, model_threads);
                 if (res.post_steps.size() != 4 || res.post_steps.back() != res.post)
                   throw std::logic_error("model: expected four post-processing steps ending in the output");
                 return std::vector<cv::Mat>{
                     sm::tools::disp_to_float(res.dp), sm::tools::disp_to_float(res.post_steps[0]),
                     sm::tools::disp_to_float(res.post_steps[1]), sm::tools::disp_to_float(res.post_steps[2]),
                     sm::tools::disp_to_float(res.post)};
               }});
  using Scene = sm::tools::Scene;
  auto peer = [&m](const std::string& name, std::function<cv::Mat(const Scene&, int)> f) {
    m.push_back({name, {name}, [f](const Scene& s, int nd) { return std::vector<cv::Mat>{f(s, nd)}; }, true});
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
                 return std::vector<cv::Mat>{d};
               },
               false,
               false});
  return m;
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
  app.add_option("dataset", dataset,
                 "dataset folder (scene subfolders with left/right/gt.png, scale.txt) or one scene folder");
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
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  app.add_option("--disp-images", disp_dir, "write <scene>_<method>.png colour disparity maps here");
  app.add_option("--methods", methods_opt,
                 "comma-separated subset of model,bm,bm-dense,sgbm,sgbm-dense,sgbm-hh,sgbm-hh-dense,binsgbm,"
                 "binsgbm-dense,results")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--results", results_dir,
                 "score another program's disparities: folder of <scene>.pfm (+inf = invalid) or <scene>.png "
                 "(value / --results-scale, 0 = invalid); adds the method 'results'");
  app.add_option("--results-scale", results_scale, "PNG results: disparity = value / scale (KITTI: 256)")
      ->capture_default_str();
  app.add_option("--synthetic", synthetic, "evaluate N synthetic scenes (sm_scene seeds 1..N) instead of a dataset");
  app.add_option("--synthetic-size", synth_size, "WxH of the synthetic scenes")->capture_default_str();
  app.add_option("--occ", occ, "model: DP occlusion penalty register")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  app.add_option("--regs", regs_file,
                 "model: register file (stereo_model --regs format: registers and compile-time parameters such as "
                 "sw_table, filter_enable, band_k, cost_shift) applied on top of the defaults; sizes and levels stay "
                 "the scene's, --occ wins when given");
  app.add_option("--threads", model_threads, "model: threads, 1..256 (same output for any count; OpenCV stays on one)")
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "no progress lines");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();
  cv::setNumThreads(1);
  if (levels != 0 && (levels < 4 || levels > 254 || levels % 2))
    throw ToolError(fmt::format("--levels {}: must be 0 or even 4..254", levels));
  if (peer_levels != 0 && (peer_levels < 16 || peer_levels > 256 || peer_levels % 16))
    throw ToolError(fmt::format("--peer-levels {}: must be 0 or a multiple of 16, 16..256", peer_levels));
  if (streak_rows.empty()) throw ToolError("--streak-rows: empty");
  if (!(results_scale > 0)) throw ToolError(fmt::format("--results-scale {}: must be positive", results_scale));
  if (!results_dir.empty() && !fs::is_directory(results_dir))
    throw ToolError(fmt::format("{}: not a directory", results_dir));

  if (model_threads < 1 || model_threads > 256)
    throw ToolError(fmt::format("--threads {}: must be 1..256", model_threads));
  std::vector<Method> methods;
  {
    const bool occ_given = app.count("--occ") > 0;
    if (!regs_file.empty() && !fs::is_regular_file(regs_file))
      throw ToolError(fmt::format("{}: no such file", regs_file));
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
    int w = 0, h = 0;
    char x = 0;
    std::stringstream ss(synth_size);
    if (!(ss >> w >> x >> h) || x != 'x')
      throw ToolError(fmt::format("--synthetic-size '{}': expected WxH", synth_size));
    const int lv = levels ? levels : 128;
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
  if (!disp_dir.empty()) {
    std::error_code ec;
    fs::create_directories(disp_dir, ec);
    if (!fs::is_directory(disp_dir)) throw ToolError(fmt::format("{}: cannot create directory", disp_dir));
  }

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
  jout["scenes"] = json::array();
  struct Cell {
    sm::tools::BadStats bad;
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
    json js = {{"name", names[i]},       {"width", sc.left.cols},
               {"height", sc.left.rows}, {"levels", lv},
               {"peer_levels", plv},     {"scene_levels", sc.levels},
               {"gt_scale", sc.scale},   {"nonocc_mask", !sc.nonocc.empty()}};
    for (const auto& m : methods) {
      ++step;
      const int mlv = m.peer ? plv : lv;
      if (!quiet)
        fmt::print(stderr, "[{}/{}] {} ({}, {} levels): {} ...\n", step, total_steps, names[i], row.size, mlv, m.name);
      const auto t0 = std::chrono::steady_clock::now();
      const std::vector<cv::Mat> est = m.run(sc, mlv);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (est.size() != m.outputs.size()) throw std::logic_error(m.name + ": wrong number of outputs");
      for (size_t k = 0; k < est.size(); ++k) {
        const std::string& out = m.outputs[k];
        Cell c{sm::tools::bad1(est[k], sc.gt, sc.nonocc), {}, m.timed && out == m.name ? ms : -1.0};
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
                              {"ms", c.ms >= 0 ? json(c.ms) : json(nullptr)}};
        row.cells.push_back(c);
        if (!disp_dir.empty())
          sm::tools::write_image_atomic((fs::path(disp_dir) / fmt::format("{}_{}.png", names[i], out)).string(),
                                        sm::tools::disp_to_colour(est[k], mlv));
      }
    }
    if (!disp_dir.empty()) {
      cv::Mat g = sc.gt.clone();
      g.setTo(-1.0f, sc.gt <= 0);
      sm::tools::write_image_atomic((fs::path(disp_dir) / fmt::format("{}_gt.png", names[i])).string(),
                                    sm::tools::disp_to_colour(g, std::max(lv, plv)));
    }
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
                                {"streak", jst},
                                {"ms", timed ? json(mean_of(k, [](const Cell& c) { return c.ms; })) : json(nullptr)}};
  }
  if (!json_path.empty()) sm::tools::write_text_atomic(json_path, jout.dump(2) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_evaluate", run, argc, argv); }
