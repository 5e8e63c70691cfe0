// sm_float_ref: the floating-point reference of the pipeline (tools/float_ref, issue 21)
// on one pair or on every scene of a dataset, with any subset of the bit-exact model's
// simplifications switched on (--simplify) and a sweep of occlusion penalties on the raw
// Hamming scale (--penalty a,b,c: the aggregation runs once per scene, the DP once per
// penalty). Dataset mode scores bad-1.0 (toolio's disp_metrics; with --subpix the
// sub-pixel output's bad-0.5 and bad-1.0) and reports the mean over all scenes and over
// the four classic ones. docs/evaluation.md, "What each fixed-point
// simplification costs".
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "float_ref/float_ref.hpp"

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

int run(int argc, char** argv) {
  sm::fref::Params p = sm::fref::Params::defaults();
  std::string left, right, dataset, simplify = "none", post = "chain", disp_file, json_path;
  std::vector<double> pen = {30};
  std::vector<int> table(p.sw_table.begin(), p.sw_table.end());
  bool quiet = false, subpix = false;
  CLI::App app{"floating-point reference of the pipeline, with the bit-exact model's simplifications switchable"};
  app.add_option("left", left, "left image (one pair; or use --dataset)");
  app.add_option("right", right, "right image");
  app.add_option("--dataset", dataset, "score every scene of this folder (../shared/datasets layout)");
  app.add_option("--simplify", simplify,
                 fmt::format("simplifications on: comma-separated {}, or all / none",
                             fmt::format("{}", fmt::join(sm::fref::simplify_names(), ","))))
      ->capture_default_str();
  app.add_option("--penalty", pen,
                 "occlusion penalties on the raw Hamming scale, comma-separated (model occ = penalty / "
                 "2^cost-shift when shift is on); one pair: the first")
      ->delimiter(',')
      ->check(sm::tools::finite_in(0, 1e6))
      ->default_str(fmt::format("{}", fmt::join(pen, ",")));
  app.add_option("--post", post, "post filters: chain (the model's F0-F3), med5x5, none")->capture_default_str();
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
  app.add_option("--sw-table", table, "2-bit weight codes 0..3 by |dI| >> 3 of the 'table' simplification (up to 32)")
      ->delimiter(',')
      ->check(sm::tools::int_in(0, 3))
      ->default_str(fmt::format("{}", fmt::join(table, ",")));
  app.add_option("--disp-file", disp_file, "one pair: disparity file (.pfm or 16-bit .png, x16)");
  app.add_flag("--subpix", subpix,
               "sub-pixel output (docs/algorithm.md 9.1, the model's default estimator; Q.4 with frac-q4): "
               "the disparity file holds it, and dataset mode scores bad-0.5 and bad-1.0 of it");
  app.add_option("--json", json_path, "dataset: write the results as JSON");
  app.add_flag("-q,--quiet", quiet, "no progress lines");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();
  try {
    p.simp = sm::fref::parse_simplify(simplify);
    p.post = sm::fref::parse_post(post);
  } catch (const std::invalid_argument& e) {
    throw ToolError(e.what());
  }
  if (table.size() > p.sw_table.size()) throw ToolError("--sw-table: more than 32 codes");
  p.sw_table.fill(0);
  std::copy(table.begin(), table.end(), p.sw_table.begin());
  if (p.census % 2 == 0 || p.sw % 2 == 0) throw ToolError("--census and --sw must be odd");
  if (!(p.gc > 0) || !(p.gp > 0)) throw ToolError("--gc and --gp must be positive");
  if (pen.empty()) throw ToolError("--penalty: empty");

  if (dataset.empty()) {
    if (left.empty() || right.empty()) throw ToolError("give LEFT RIGHT or --dataset DIR");
    if (disp_file.empty()) throw ToolError("one pair: --disp-file is required");
    const sm::Image8 l = sm::tools::load_grey(left), r = sm::tools::load_grey(right);
    if (l.w != r.w || l.h != r.h)
      throw ToolError(fmt::format("{}: size {}x{} differs from {}'s {}x{}", right, r.w, r.h, left, l.w, l.h));
    sm::tools::write_disparity_file(disp_file, scored_output(l, r, p, pen[0], subpix));
    return 0;
  }
  if (!left.empty()) throw ToolError("--dataset: no LEFT RIGHT images");

  const auto dirs = sm::tools::list_scenes(dataset);
  if (dirs.empty()) throw ToolError(fmt::format("{}: no scenes", dataset));
  json jout;
  jout["dataset"] = dataset;
  jout["simplify"] = sm::fref::simplify_string(p.simp);
  jout["params"] = {{"census", p.census},
                    {"sw", p.sw},
                    {"levels", p.levels},
                    {"cost_shift", p.cost_shift},
                    {"ad_shift", p.ad_shift},
                    {"ad_max", p.ad_max},
                    {"smooth_t", p.smooth_t},
                    {"gc", p.gc},
                    {"gp", p.gp},
                    {"post", post},
                    {"sw_table", p.sw_table},
                    {"penalties", pen}};
  jout["scenes"] = json::array();
  jout["subpix"] = subpix;
  std::vector<double> sum(pen.size(), 0), sum_c(pen.size(), 0), sum05(pen.size(), 0);
  int n = 0, n_c = 0;
  std::string head = fmt::format("{:<12}", "penalty");
  for (double v : pen) head += subpix ? fmt::format(" {:>13g}", v) : fmt::format(" {:>7g}", v);
  fmt::print("simplify: {}{}\n{}\n{}\n", sm::fref::simplify_string(p.simp),
             subpix ? "; sub-pixel output, bad-0.5/bad-1.0 %" : "; bad-1.0 %", head, std::string(head.size(), '-'));
  for (const auto& d : dirs) {
    const sm::tools::Scene sc = sm::tools::load_scene(d);
    const std::string name = fs::path(d).filename().string();
    if (!quiet) fmt::print(stderr, "{} ({}x{}) ...\n", name, sc.left.cols, sc.left.rows);
    const auto vol = sm::fref::aggregate(sm::tools::to_image8(sc.left), sm::tools::to_image8(sc.right), p);
    std::string line = fmt::format("{:<12}", name);
    json js = {{"name", name}, {"bad1_pct", json::array()}};
    if (subpix) js["bad05_pct"] = json::array();
    for (size_t k = 0; k < pen.size(); ++k) {
      const sm::tools::DispMetrics m = sm::tools::disp_metrics(scored_output(vol, pen[k], p, subpix), sc.gt, sc.nonocc);
      const double b = m.pct(m.bad1), b05 = m.pct(m.bad05);
      sum[k] += b;
      sum05[k] += b05;
      if (is_classic(name)) sum_c[k] += b;
      js["bad1_pct"].push_back(b);
      if (subpix) js["bad05_pct"].push_back(b05);
      line += subpix ? fmt::format(" {:>6.2f}/{:<6.2f}", b05, b) : fmt::format(" {:>7.2f}", b);
    }
    ++n;
    if (is_classic(name)) ++n_c;
    fmt::print("{}\n", line);
    jout["scenes"].push_back(js);
  }
  std::string mean = fmt::format("{:<12}", fmt::format("mean ({})", n)), mean_c = fmt::format("{:<12}", "mean classic");
  size_t best = 0;
  for (size_t k = 0; k < pen.size(); ++k) {
    mean += subpix ? fmt::format(" {:>6.2f}/{:<6.2f}", sum05[k] / n, sum[k] / n) : fmt::format(" {:>7.2f}", sum[k] / n);
    const std::string c = n_c ? fmt::format("{:.2f}", sum_c[k] / n_c) : "-";
    mean_c += subpix ? fmt::format(" {:>13}", c) : fmt::format(" {:>7}", c);
    if (sum[k] < sum[best]) best = k;
  }
  fmt::print("{}\n{}\n", mean, mean_c);
  fmt::print("best penalty on all {} scenes: {:g} -> mean {:.2f}, classic {}\n", n, pen[best], sum[best] / n,
             n_c ? fmt::format("{:.2f}", sum_c[best] / n_c) : "-");
  for (size_t k = 0; k < pen.size(); ++k) {
    jout["mean"].push_back(sum[k] / n);
    if (subpix) jout["mean_bad05"].push_back(sum05[k] / n);
    jout["mean_classic"].push_back(n_c ? json(sum_c[k] / n_c) : json(nullptr));
  }
  jout["best"] = {
      {"penalty", pen[best]}, {"mean", sum[best] / n}, {"mean_classic", n_c ? json(sum_c[best] / n_c) : json(nullptr)}};
  if (!json_path.empty()) sm::tools::write_text_atomic(json_path, jout.dump(2) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_float_ref", run, argc, argv); }
