// sm_evaluate: accuracy (bad-1.0) and single-thread run time of the reference model and
// of OpenCV's StereoBM, StereoSGBM and StereoBinarySGBM (opencv_contrib "stereo") on a
// stereo dataset in the ../shared/datasets layout, or on synthetic scenes from the
// sm_scene generator. Invalid outputs count as bad (dense comparison). Disparity files made
// by another program (--results: <scene>.pfm or <scene>.png) are scored the same way.
// docs/evaluation.md.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/stereo.hpp>
#include <sstream>

#include "common/sm_io.hpp"
#include "common/sm_scenegen.hpp"
#include "pipeline.hpp"

namespace {

namespace fs = std::filesystem;
using sm::tools::ToolError;
using json = nlohmann::json;

struct Method {
  std::string name;
  std::function<cv::Mat(const sm::tools::Scene&, int)> run;  // (scene, levels) -> CV_32F, < 0 invalid
  bool timed = true;                                         // false: read from a file, no run time
};

// OpenCV matchers produce 16x fixed point with values below minDisparity (0) invalid.
cv::Mat from_fixed16(const cv::Mat& d16) {
  cv::Mat f;
  d16.convertTo(f, CV_32F, 1.0 / 16);
  f.setTo(-1.0f, d16 < 0);
  return f;
}

int round16(int levels) { return (levels + 15) / 16 * 16; }

// A scene's disparity file in the --results folder: <scene>.pfm or <scene>.png.
std::string result_file(const std::string& dir, const std::string& scene) {
  const fs::path pfm = fs::path(dir) / (scene + ".pfm"), png = fs::path(dir) / (scene + ".png");
  std::error_code ec;
  const bool has_pfm = fs::exists(pfm, ec), has_png = fs::exists(png, ec);
  if (has_pfm && has_png) throw ToolError(fmt::format("{}: both {}.pfm and {}.png exist; keep one", dir, scene, scene));
  if (!has_pfm && !has_png) throw ToolError(fmt::format("{}: no {}.pfm or {}.png", dir, scene, scene));
  return (has_pfm ? pfm : png).string();
}

std::vector<Method> all_methods(int occ, const std::string& results_dir, double results_scale) {
  std::vector<Method> m;
  m.push_back({"model", [occ](const sm::tools::Scene& s, int levels) {
                 sm::HwConfig hw;  // paper defaults: CENSUS 15, SW 5
                 hw.disp = levels;
                 hw.max_width = s.left.cols;
                 hw.max_height = s.left.rows;
                 sm::Regs regs = sm::Regs::defaults(hw);
                 regs.occ = static_cast<uint8_t>(occ);
                 const auto res =
                     sm::run_pipeline(sm::tools::to_image8(s.left), sm::tools::to_image8(s.right), hw, regs, false);
                 return sm::tools::disp_to_float(res.post);
               }});
  m.push_back({"bm", [](const sm::tools::Scene& s, int levels) {
                 auto bm = cv::StereoBM::create(round16(levels), 15);
                 cv::Mat d;
                 bm->compute(s.left, s.right, d);
                 return from_fixed16(d);
               }});
  m.push_back({"sgbm", [](const sm::tools::Scene& s, int levels) {
                 const int bs = 5;  // parameters of OpenCV's stereo_match sample
                 auto sg = cv::StereoSGBM::create(0, round16(levels), bs, 8 * bs * bs, 32 * bs * bs, 1, 63, 10, 100, 32,
                                                  cv::StereoSGBM::MODE_SGBM);
                 cv::Mat d;
                 sg->compute(s.left, s.right, d);
                 return from_fixed16(d);
               }});
  m.push_back({"binsgbm", [](const sm::tools::Scene& s, int levels) {
                 auto sg = cv::stereo::StereoBinarySGBM::create(0, round16(levels), 9, 100, 1000, 1, 0, 5, 400, 200);
                 cv::Mat d;
                 sg->compute(s.left, s.right, d);
                 return from_fixed16(d);
               }});
  // Another program's disparities, read from --results (PFM: +inf invalid; PNG: value /
  // --results-scale, 0 invalid), scored exactly like the methods above.
  m.push_back({"results",
               [results_dir, results_scale](const sm::tools::Scene& s, int) {
                 if (results_dir.empty()) throw ToolError("--methods results: no --results folder given");
                 const std::string f = result_file(results_dir, s.name);
                 cv::Mat d = sm::tools::read_disparity_file(f, results_scale);
                 if (d.size() != s.left.size())
                   throw ToolError(fmt::format("{}: size {}x{} differs from the scene's {}x{}", f, d.cols, d.rows,
                                               s.left.cols, s.left.rows));
                 return d;
               },
               false});
  return m;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) v.push_back(item);
  return v;
}

int run(int argc, char** argv) {
  std::string dataset, scenes_opt, json_path, disp_dir, methods_opt = "model,bm,sgbm,binsgbm";
  std::string synth_size = fmt::format("{}x{}", sm::HwConfig{}.max_width, sm::HwConfig{}.max_height), results_dir;
  double results_scale = 16;
  int levels = sm::HwConfig{}.disp, synthetic = 0, occ = sm::Regs{}.occ;
  bool quiet = false;
  CLI::App app{"bad-1.0 and run time of the model and OpenCV matchers on a stereo dataset"};
  app.add_option("dataset", dataset,
                 "dataset folder (scene subfolders with left/right/gt.png, scale.txt) or one scene folder");
  app.add_option("--scenes", scenes_opt, "comma-separated scene names (default: all)");
  app.add_option("--json", json_path, "write the results as JSON");
  app.add_option("--levels", levels, "disparity levels of every method (0: per scene, from scale.txt)")
      ->capture_default_str();
  app.add_option("--disp-images", disp_dir, "write <scene>_<method>.png colour disparity maps here");
  app.add_option("--methods", methods_opt, "comma-separated subset of model,bm,sgbm,binsgbm,results")
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
  app.add_flag("-q,--quiet", quiet, "no progress lines");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  sm::tools::quiet_opencv();
  cv::setNumThreads(1);
  if (levels != 0 && (levels < 4 || levels > 254 || levels % 2))
    throw ToolError(fmt::format("--levels {}: must be 0 or even 4..254", levels));
  if (!(results_scale > 0)) throw ToolError(fmt::format("--results-scale {}: must be positive", results_scale));
  if (!results_dir.empty() && !fs::is_directory(results_dir))
    throw ToolError(fmt::format("{}: not a directory", results_dir));

  std::vector<Method> methods;
  {
    const auto all = all_methods(occ, results_dir, results_scale);
    auto names_opt = split(methods_opt);
    if (!results_dir.empty() && std::find(names_opt.begin(), names_opt.end(), "results") == names_opt.end())
      names_opt.push_back("results");
    for (const auto& n : names_opt) {
      auto it = std::find_if(all.begin(), all.end(), [&](const Method& m) { return m.name == n; });
      if (it == all.end()) throw ToolError(fmt::format("--methods: unknown method '{}'", n));
      if (n == "results" && results_dir.empty()) throw ToolError("--methods results: no --results folder given");
      methods.push_back(*it);
    }
    if (methods.empty()) throw ToolError("--methods: empty");
  }

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
    const auto wanted = split(scenes_opt);
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
  jout["threads"] = 1;
  jout["scenes"] = json::array();
  std::map<std::string, double> sum_bad, sum_ms;
  struct Row {
    std::string name;
    std::string size;
    int levels;
    std::vector<std::pair<sm::tools::BadStats, double>> r;
  };
  std::vector<Row> rows;
  const size_t total_steps = loaders.size() * methods.size();
  size_t step = 0;
  for (size_t i = 0; i < loaders.size(); ++i) {
    sm::tools::Scene sc = loaders[i]();
    sc.name = names[i];  // --results files are looked up by this name
    const int lv = levels ? levels : std::min(254, (sc.levels + 1) / 2 * 2);
    Row row{names[i], fmt::format("{}x{}", sc.left.cols, sc.left.rows), lv, {}};
    json js = {{"name", names[i]},          {"width", sc.left.cols}, {"height", sc.left.rows},           {"levels", lv},
               {"scene_levels", sc.levels}, {"gt_scale", sc.scale},  {"nonocc_mask", !sc.nonocc.empty()}};
    for (const auto& m : methods) {
      ++step;
      if (!quiet)
        fmt::print(stderr, "[{}/{}] {} ({}, {} levels): {} ...\n", step, total_steps, names[i], row.size, lv, m.name);
      const auto t0 = std::chrono::steady_clock::now();
      const cv::Mat est = m.run(sc, lv);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      const auto st = sm::tools::bad1(est, sc.gt, sc.nonocc);
      row.r.emplace_back(st, m.timed ? ms : -1.0);
      sum_bad[m.name] += st.bad_pct();
      sum_ms[m.name] += ms;
      js["methods"][m.name] = {{"bad1_pct", st.bad_pct()},
                               {"evaluated", st.evaluated},
                               {"bad", st.bad},
                               {"invalid", st.invalid},
                               {"ms", m.timed ? json(ms) : json(nullptr)}};
      if (!disp_dir.empty())
        sm::tools::write_image_atomic((fs::path(disp_dir) / fmt::format("{}_{}.png", names[i], m.name)).string(),
                                      sm::tools::disp_to_colour(est, lv));
    }
    if (!disp_dir.empty()) {
      cv::Mat g = sc.gt.clone();
      g.setTo(-1.0f, sc.gt <= 0);
      sm::tools::write_image_atomic((fs::path(disp_dir) / fmt::format("{}_gt.png", names[i])).string(),
                                    sm::tools::disp_to_colour(g, lv));
    }
    jout["scenes"].push_back(js);
    rows.push_back(row);
  }

  // Table: bad-1.0 % (invalid share in brackets) and ms per method.
  std::string head = fmt::format("{:<12} {:>8} {:>6}", "scene", "size", "levels");
  for (const auto& m : methods) head += fmt::format(" | {:>18} {:>8}", m.name + " bad1% (inv%)", "ms");
  fmt::print("{}\n{}\n", head, std::string(head.size(), '-'));
  for (const auto& row : rows) {
    std::string line = fmt::format("{:<12} {:>8} {:>6}", row.name, row.size, row.levels);
    for (const auto& [st, ms] : row.r)
      line +=
          fmt::format(" | {:>10.2f} ({:>5.1f}) {:>8}", st.bad_pct(),
                      st.evaluated ? 100.0 * st.invalid / st.evaluated : 0.0, ms < 0 ? "-" : fmt::format("{:.0f}", ms));
    fmt::print("{}\n", line);
  }
  std::string mean = fmt::format("{:<12} {:>8} {:>6}", "mean", "", "");
  for (const auto& m : methods) {
    const double n = static_cast<double>(rows.size());
    mean += fmt::format(" | {:>10.2f} {:>7} {:>8}", sum_bad[m.name] / n, "",
                        m.timed ? fmt::format("{:.0f}", sum_ms[m.name] / n) : "-");
    jout["mean"][m.name] = {{"bad1_pct", sum_bad[m.name] / n},
                            {"ms", m.timed ? json(sum_ms[m.name] / n) : json(nullptr)}};
  }
  fmt::print("{}\n", mean);
  if (!json_path.empty()) sm::tools::write_text_atomic(json_path, jout.dump(2) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_evaluate", run, argc, argv); }
