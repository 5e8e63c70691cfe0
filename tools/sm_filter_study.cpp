// Filter study (docs/algorithm.md section 7): runs the reference pipeline on stereo
// scenes with the post-processing off, then measures bad-1.0 of the raw DP output and
// of candidate streak filters and chains, so each filter of the chain earns its place.
//   sm_filter_study [--datasets DIR] [--synthetic N] [--disp 128] [--json out.json]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_scenegen.hpp"
#include "pipeline.hpp"
#include "post.hpp"

using namespace sm;
using namespace sm::tools;

namespace {
using Filter = std::function<DispImage(const DispImage&, const HwConfig&)>;
struct Candidate {
  std::string name;
  std::vector<Filter> chain;
};
Filter rk(int ry, int rx, int rank) {
  return [ry, rx, rank](const DispImage& d, const HwConfig& hw) { return post_rank(d, hw, ry, rx, rank); };
}
Filter med(int ry, int rx) {
  return [ry, rx](const DispImage& d, const HwConfig& hw) { return post_median(d, hw, ry, rx); };
}

int run(int argc, char** argv) {
  CLI::App app{"Measure bad-1.0 of the DP output before/after candidate streak filters"};
  std::string datasets;
  int synthetic = 0;
  int disp = sm::HwConfig{}.disp;
  std::string json_out;
  std::string dump_dir;
  app.add_option("--datasets", datasets, "folder of scene folders (e.g. ../shared/datasets)");
  app.add_option("--synthetic", synthetic, "number of synthetic 320x240 scenes")->check(sm::tools::int_in(0, 100));
  app.add_option("--disp", disp, "disparity levels (DISP)")->check(sm::tools::int_in(4, 254))->capture_default_str();
  app.add_option("--json", json_out, "write the table as JSON");
  app.add_option("--dump", dump_dir, "write <scene>_dp.png and <scene>_err.png (bad pixels) here");
  if (const auto rc = parse_args(app, argc, argv)) return *rc;
  quiet_opencv();

  // The chain (section 7) is F1 vmed5 -> F2 med3x3 -> F3 med5x3 (rows x columns); the
  // rest are the alternatives it was chosen against and leave-one-out variants.
  const std::vector<Candidate> cands = {
      {"dp (no filter)", {}},
      {"F1 vmed5", {med(2, 0)}},
      {"F1+F2 vmed5+med3x3", {med(2, 0), med(1, 1)}},
      {"F1+F2+F3 (chain)", {med(2, 0), med(1, 1), med(2, 1)}},
      {"F2 med3x3 alone", {med(1, 1)}},
      {"F3 med5x3 alone", {med(2, 1)}},
      {"F2+F3 (no F1)", {med(1, 1), med(2, 1)}},
      {"F1+F3 (no F2)", {med(2, 0), med(2, 1)}},
      {"vmed3", {med(1, 0)}},
      {"vmed7", {med(3, 0)}},
      {"med5x5", {med(2, 2)}},
      {"med7x3", {med(3, 1)}},
      {"hmed5 (1x5)", {med(0, 2)}},
      {"vmed5+vmed5", {med(2, 0), med(2, 0)}},
      {"vmed5+med3x3+hmed5", {med(2, 0), med(1, 1), med(0, 2)}},
      {"vmed5+med3x3+med3x3", {med(2, 0), med(1, 1), med(1, 1)}},
      {"vmed7+med5x3+med3x3", {med(3, 0), med(2, 1), med(1, 1)}},
      {"hmin3 (erosion 1x3)", {rk(0, 1, 0)}},
      {"3x3 rank 3", {rk(1, 1, 3)}},
      {"vmed5+med3x3+hmin3", {med(2, 0), med(1, 1), rk(0, 1, 0)}},
  };

  struct Input {
    std::string name;
    Image8 left, right;
    cv::Mat gt, mask;
  };
  std::vector<Input> inputs;
  if (!datasets.empty())
    for (const std::string& dir : list_scenes(datasets)) {
      if (!is_scene_dir(dir)) continue;
      Scene s = load_scene(dir);
      inputs.push_back({s.name, to_image8(s.left), to_image8(s.right), s.gt, s.nonocc});
    }
  for (int i = 0; i < synthetic; ++i) {
    SceneParams p;
    p.levels = disp;
    p.seed = 100 + i;
    p.noise = 2.0;
    SyntheticScene s = render_scene(p);
    inputs.push_back({fmt::format("synthetic{}", i), to_image8(s.left), to_image8(s.right), s.gt, s.nonocc});
  }
  if (inputs.empty()) throw ToolError("no scenes (give --datasets DIR or --synthetic N)");

  nlohmann::json js = nlohmann::json::array();
  std::vector<double> sum(cands.size(), 0.0);
  std::vector<std::vector<double>> table(cands.size()), table_all(cands.size());
  for (const auto& in : inputs) {
    HwConfig hw;
    hw.max_width = in.left.w;
    hw.max_height = in.left.h;
    hw.disp = disp;
    Regs regs = Regs::defaults(hw);
    regs.filter_enable = 0;
    const PipelineResult r = run_pipeline(in.left, in.right, hw, regs, false);
    if (!dump_dir.empty()) {
      const cv::Mat f = disp_to_float(r.dp);
      cv::Mat err(f.size(), CV_8UC3, cv::Scalar(0, 0, 0));
      for (int y = 0; y < f.rows; ++y)
        for (int x = 0; x < f.cols; ++x) {
          const float g = in.gt.at<float>(y, x);
          const bool eval = g > 0 && (in.mask.empty() || in.mask.at<uint8_t>(y, x));
          const float e = f.at<float>(y, x);
          if (!eval) continue;
          const bool bad = e < 0 || std::fabs(e - g) > 1.0f;
          err.at<cv::Vec3b>(y, x) = bad ? (e > g ? cv::Vec3b(0, 0, 255) : cv::Vec3b(255, 0, 0)) : cv::Vec3b(80, 80, 80);
        }
      write_image_atomic(dump_dir + "/" + in.name + "_dp.png", disp_to_grey(f, disp));
      write_image_atomic(dump_dir + "/" + in.name + "_err.png", err);
    }
    for (size_t c = 0; c < cands.size(); ++c) {
      DispImage d = r.dp;
      for (const Filter& f : cands[c].chain) d = f(d, hw);
      const BadStats b = bad1(disp_to_float(d), in.gt, in.mask);
      const BadStats ba = bad1(disp_to_float(d), in.gt, cv::Mat());
      table[c].push_back(b.bad_pct());
      table_all[c].push_back(ba.bad_pct());
      js.push_back({{"scene", in.name}, {"chain", cands[c].name}, {"bad1", b.bad_pct()}, {"bad1_all", ba.bad_pct()}});
    }
    fmt::print(stderr, "{} done\n", in.name);
  }
  auto print_table = [&](const char* title, const std::vector<std::vector<double>>& t) {
    fmt::print("{}\n{:<26}", title, "chain");
    for (const auto& in : inputs) fmt::print(" {:>11}", in.name);
    fmt::print(" {:>8}\n", "mean");
    for (size_t c = 0; c < cands.size(); ++c) {
      fmt::print("{:<26}", cands[c].name);
      double s = 0;
      for (double v : t[c]) {
        fmt::print(" {:>11.3f}", v);
        s += v;
      }
      fmt::print(" {:>8.3f}\n", s / static_cast<double>(t[c].size()));
    }
  };
  print_table("bad-1.0 % (known pixels, nonocc mask where present)", table);
  print_table("bad-1.0 % (all known pixels, occluded included)", table_all);
  if (!json_out.empty()) write_text_atomic(json_out, js.dump(1));
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return guarded_main("sm_filter_study", run, argc, argv); }
