// sm_float_ref: the floating-point reference of the pipeline (tools/float_ref, issue 21)
// on one pair or on every scene of a dataset, with any subset of the bit-exact model's
// simplifications switched on (--simplify) and a sweep of occlusion penalties on the raw
// Hamming scale (--penalty a,b,c: the aggregation runs once per scene, the DP once per
// penalty). Dataset mode scores bad-1.0 (toolio's disp_metrics; with --subpix the
// sub-pixel output's bad-0.5 and bad-1.0) and reports the mean over all scenes and over
// the four classic ones. docs/evaluation.md, "What each fixed-point
// simplification costs". The options of the other mode are refused when parsing
// (--dataset excludes LEFT RIGHT and --disp-file, --json needs --dataset), and the output
// is checked before any work (docs/robustness.md).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_outputs.hpp"
#include "float_ref/float_ref.hpp"
#include "lower_case.hpp"

namespace {

namespace fs = std::filesystem;
using sm::tools::ToolError;
using json = nlohmann::json;

bool is_classic(const std::string& n) { return n == "cones" || n == "teddy" || n == "tsukuba" || n == "venus"; }

// The disparity of one penalty as float pixels: the post filters' integer output, or with
// `subpix` the sub-pixel output after them, smoothed.
cv::Mat scored_output(const sm::fref::CostVol& vol, double penalty, const sm::fref::Params& p, bool subpix) {
  const sm::DispImage dp = sm::fref::trellis(vol, penalty, p), out = sm::fref::post(dp, p);
  if (!subpix) return sm::tools::disp_to_float(out);
  std::vector<float> v = sm::fref::smooth(sm::fref::subpix(vol, dp, out, p), vol.w, vol.h, p);
  return cv::Mat(vol.h, vol.w, CV_32F, v.data()).clone();
}
cv::Mat scored_output(const sm::Image8& l, const sm::Image8& r, const sm::fref::Params& p, double penalty,
                      bool subpix) {
  return scored_output(sm::fref::aggregate(l, r, p), penalty, p, subpix);
}

struct Options {
  sm::fref::Params p = sm::fref::Params::defaults();
  std::string left, right, dataset, post = "chain", disp_file, json_path;
  std::vector<std::string> simplify = {"none"};
  std::vector<double> pen = {30};
  std::vector<int> table;
  bool quiet = false, subpix = false;
};

// The mode's options: one pair (LEFT RIGHT --disp-file) or a dataset (--dataset, --json).
void add_mode_options(CLI::App& app, Options& o) {
  CLI::Option* left = app.add_option("left", o.left, "left image (one pair; or use --dataset)");
  CLI::Option* right = app.add_option("right", o.right, "right image");
  CLI::Option* dataset =
      app.add_option("--dataset", o.dataset, "score every scene of this folder (../shared/datasets layout)");
  CLI::Option* disp = app.add_option("--disp-file", o.disp_file, "one pair: disparity file (.pfm or 16-bit .png, x16)");
  app.add_option("--json", o.json_path, "dataset: write the results as JSON")->needs(dataset);
  dataset->excludes(left)->excludes(right)->excludes(disp);
}

void add_algorithm_options(CLI::App& app, Options& o) {
  sm::fref::Params& p = o.p;
  app.add_option("--simplify", o.simplify,
                 fmt::format("simplifications on: comma-separated {}, or all / none",
                             fmt::format("{}", fmt::join(sm::fref::simplify_names(), ","))))
      ->delimiter(',')
      ->default_str("none");
  app.add_option("--penalty", o.pen,
                 "occlusion penalties on the raw Hamming scale, comma-separated (model occ = penalty / "
                 "2^cost-shift when shift is on); one pair: the first")
      ->delimiter(',')
      ->check(sm::tools::finite_in(0, 1e6))
      ->default_str(fmt::format("{}", fmt::join(o.pen, ",")));
  app.add_option("--post", o.post, "post filters: chain (the model's F0-F3), med5x5, none")->capture_default_str();
  app.add_option("--levels", p.levels, "disparity levels")->check(sm::tools::int_in(2, 256))->capture_default_str();
  app.add_option("--census", p.census, "census window side")->check(sm::tools::int_in(3, 15))->capture_default_str();
  app.add_option("--sw", p.sw, "support-weight window side")->check(sm::tools::int_in(1, 7))->capture_default_str();
  app.add_option("--cost-shift", p.cost_shift, "COST_SHIFT of the 'shift' simplification")
      ->check(sm::tools::int_in(0, 4))
      ->capture_default_str();
  app.add_option("--ad-shift", p.ad_shift, "the cost's intensity term: |left - right| >> AD_SHIFT")
      ->check(sm::tools::int_in(0, 7))
      ->capture_default_str();
  app.add_option("--ad-max", p.ad_max, "the intensity term's cap (0: census only)")
      ->check(sm::tools::int_in(0, 15))
      ->capture_default_str();
  app.add_option("--smooth-t", p.smooth_t,
                 "with --subpix: smoothing threshold in pixels (docs/algorithm.md 9.7; 0: off)")
      ->check(sm::tools::finite_in(0, 4))
      ->capture_default_str();
  app.add_option("--gc", p.gc, "float weights: intensity scale")
      ->check(sm::tools::finite_in(1e-6, 1e6))
      ->capture_default_str();
  app.add_option("--gp", p.gp, "float weights: spatial scale")
      ->check(sm::tools::finite_in(1e-6, 1e6))
      ->capture_default_str();
  o.table.assign(p.sw_table.begin(), p.sw_table.end());
  app.add_option("--sw-table", o.table, "2-bit weight codes 0..3 by |dI| >> 3 of the 'table' simplification (up to 32)")
      ->delimiter(',')
      ->check(sm::tools::int_in(0, 3))
      ->default_str(fmt::format("{}", fmt::join(o.table, ",")));
  app.add_flag("--subpix", o.subpix,
               "sub-pixel output (docs/algorithm.md 9.1, the model's default estimator; Q.4 with frac-q4): "
               "the disparity file holds it, and dataset mode scores bad-0.5 and bad-1.0 of it");
}

// The values CLI11 does not check, into o.p.
void check_options(Options& o) {
  sm::fref::Params& p = o.p;
  try {
    p.simp = sm::fref::parse_simplify(fmt::format("{}", fmt::join(o.simplify, ",")));
    p.post = sm::fref::parse_post(o.post);
  } catch (const std::invalid_argument& e) {
    throw ToolError(e.what());
  }
  if (o.table.size() > p.sw_table.size()) throw ToolError("--sw-table: more than 32 codes");
  p.sw_table.fill(0);
  std::copy(o.table.begin(), o.table.end(), p.sw_table.begin());
  if (p.census % 2 == 0 || p.sw % 2 == 0) throw ToolError("--census and --sw must be odd");
  if (!(p.gc > 0) || !(p.gp > 0)) throw ToolError("--gc and --gp must be positive");
  if (o.pen.empty()) throw ToolError("--penalty: empty");
}

// The mode's inputs are given, and its output can be written (before any work).
void check_mode(const Options& o) {
  if (o.dataset.empty()) {
    if (o.left.empty() || o.right.empty()) throw ToolError("give LEFT RIGHT or --dataset DIR");
    if (o.disp_file.empty()) throw ToolError("one pair: --disp-file is required");
  }
  sm::tools::check_outputs({{"--disp-file", o.disp_file}, {"--json", o.json_path}}, false,
                           {{"LEFT", o.left}, {"RIGHT", o.right}});
  const std::string ext = sm::lower_extension(o.disp_file);
  if (!o.disp_file.empty() && ext != ".pfm" && ext != ".png")
    throw ToolError(fmt::format("{}: --disp-file must end in .pfm or .png", o.disp_file));
}

int run_pair(const Options& o) {
  const sm::Image8 l = sm::tools::load_grey(o.left), r = sm::tools::load_grey(o.right);
  if (l.w != r.w || l.h != r.h)
    throw ToolError(fmt::format("{}: size {}x{} differs from {}'s {}x{}", o.right, r.w, r.h, o.left, l.w, l.h));
  sm::tools::write_disparity_file(o.disp_file, scored_output(l, r, o.p, o.pen[0], o.subpix));
  return 0;
}

json params_json(const Options& o) {
  const sm::fref::Params& p = o.p;
  return {{"census", p.census},
          {"sw", p.sw},
          {"levels", p.levels},
          {"cost_shift", p.cost_shift},
          {"ad_shift", p.ad_shift},
          {"ad_max", p.ad_max},
          {"smooth_t", p.smooth_t},
          {"gc", p.gc},
          {"gp", p.gp},
          {"post", o.post},
          {"sw_table", p.sw_table},
          {"penalties", o.pen}};
}

// The sums over the scenes, one entry per penalty.
struct Sums {
  std::vector<double> all, classic, bad05;
  int n = 0, n_c = 0;
};

// Scores one scene at every penalty: prints its line, adds to `s`, returns its JSON.
json score_scene(const std::string& dir, const Options& o, Sums& s) {
  const sm::tools::Scene sc = sm::tools::load_scene(dir);
  const std::string name = fs::path(dir).filename().string();
  if (!o.quiet) fmt::print(stderr, "{} ({}x{}) ...\n", name, sc.left.cols, sc.left.rows);
  const auto vol = sm::fref::aggregate(sm::tools::to_image8(sc.left), sm::tools::to_image8(sc.right), o.p);
  std::string line = fmt::format("{:<12}", name);
  json js = {{"name", name}, {"bad1_pct", json::array()}};
  if (o.subpix) js["bad05_pct"] = json::array();
  for (size_t k = 0; k < o.pen.size(); ++k) {
    const sm::tools::DispMetrics m =
        sm::tools::disp_metrics(scored_output(vol, o.pen[k], o.p, o.subpix), sc.gt, sc.nonocc);
    const double b = m.pct(m.bad1), b05 = m.pct(m.bad05);
    s.all[k] += b;
    s.bad05[k] += b05;
    if (is_classic(name)) s.classic[k] += b;
    js["bad1_pct"].push_back(b);
    if (o.subpix) js["bad05_pct"].push_back(b05);
    line += o.subpix ? fmt::format(" {:>6.2f}/{:<6.2f}", b05, b) : fmt::format(" {:>7.2f}", b);
  }
  ++s.n;
  if (is_classic(name)) ++s.n_c;
  fmt::print("{}\n", line);
  return js;
}

// Prints the means and the best penalty; adds them to `jout`.
void summarize(const Options& o, const Sums& s, json& jout) {
  const int n = s.n, n_c = s.n_c;
  std::string mean = fmt::format("{:<12}", fmt::format("mean ({})", n)), mean_c = fmt::format("{:<12}", "mean classic");
  size_t best = 0;
  for (size_t k = 0; k < o.pen.size(); ++k) {
    mean += o.subpix ? fmt::format(" {:>6.2f}/{:<6.2f}", s.bad05[k] / n, s.all[k] / n)
                     : fmt::format(" {:>7.2f}", s.all[k] / n);
    const std::string c = n_c ? fmt::format("{:.2f}", s.classic[k] / n_c) : "-";
    mean_c += o.subpix ? fmt::format(" {:>13}", c) : fmt::format(" {:>7}", c);
    if (s.all[k] < s.all[best]) best = k;
    jout["mean"].push_back(s.all[k] / n);
    if (o.subpix) jout["mean_bad05"].push_back(s.bad05[k] / n);
    jout["mean_classic"].push_back(n_c ? json(s.classic[k] / n_c) : json(nullptr));
  }
  fmt::print("{}\n{}\n", mean, mean_c);
  fmt::print("best penalty on all {} scenes: {:g} -> mean {:.2f}, classic {}\n", n, o.pen[best], s.all[best] / n,
             n_c ? fmt::format("{:.2f}", s.classic[best] / n_c) : "-");
  jout["best"] = {{"penalty", o.pen[best]},
                  {"mean", s.all[best] / n},
                  {"mean_classic", n_c ? json(s.classic[best] / n_c) : json(nullptr)}};
}

int run_dataset(const Options& o) {
  const auto dirs = sm::tools::list_scenes(o.dataset);
  if (dirs.empty()) throw ToolError(fmt::format("{}: no scenes", o.dataset));
  json jout;
  jout["dataset"] = o.dataset;
  jout["simplify"] = sm::fref::simplify_string(o.p.simp);
  jout["params"] = params_json(o);
  jout["scenes"] = json::array();
  jout["subpix"] = o.subpix;
  std::string head = fmt::format("{:<12}", "penalty");
  for (double v : o.pen) head += o.subpix ? fmt::format(" {:>13g}", v) : fmt::format(" {:>7g}", v);
  fmt::print("simplify: {}{}\n{}\n{}\n", sm::fref::simplify_string(o.p.simp),
             o.subpix ? "; sub-pixel output, bad-0.5/bad-1.0 %" : "; bad-1.0 %", head, std::string(head.size(), '-'));
  Sums s;
  s.all.assign(o.pen.size(), 0);
  s.classic = s.bad05 = s.all;
  for (const auto& d : dirs) jout["scenes"].push_back(score_scene(d, o, s));
  summarize(o, s, jout);
  if (!o.json_path.empty()) sm::tools::write_text_atomic(o.json_path, jout.dump(2) + "\n");
  return 0;
}

int run(int argc, char** argv) {
  Options o;
  CLI::App app{"floating-point reference of the pipeline, with the bit-exact model's simplifications switchable"};
  add_mode_options(app, o);
  add_algorithm_options(app, o);
  app.add_flag("-q,--quiet", o.quiet, "no progress lines");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();
  check_options(o);
  check_mode(o);
  return o.dataset.empty() ? run_pair(o) : run_dataset(o);
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_float_ref", run, argc, argv); }
