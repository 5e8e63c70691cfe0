// Output-stage study (docs/evaluation.md, "Sub-pixel, validity and confidence"): runs the
// reference pipeline once per scene, keeps the per-pixel evidence and the post-processed
// disparity, then scores the sub-pixel estimators, validity rules and confidence formulas
// of model/outword.hpp on all scenes at once (14-scene means), so each default is chosen
// on every scene.
//   sm_output_study DATASET [--scenes a,b] [--study subpix,valid,conf,bound,speckle,speckle-conf,dp-margin,
//   window-conf]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_outputs.hpp"
#include "confidence.hpp"
#include "configs.hpp"
#include "output_frame.hpp"
#include "outword.hpp"
#include "pipeline.hpp"
#include "row_support.hpp"
#include "smooth.hpp"
#include "sm_dp_margin.hpp"
#include "sm_output_bound.hpp"
#include "sm_speckle.hpp"
#include "sm_speckle_table.hpp"
#include "sm_window_support.hpp"
#include "speckle.hpp"

using namespace sm;
using namespace sm::tools;

namespace {

using Frame = OutputFrame;

bool classic(const std::string& n) { return n == "tsukuba" || n == "venus" || n == "teddy" || n == "cones"; }

// The margin (dp_margin) of a row's levels d from one cue's per-level costs m.
void row_margins(const std::vector<int64_t>& m, const std::vector<int>& d, int levels, int32_t* out) {
  for (size_t x = 0; x < d.size(); ++x)
    out[x] = static_cast<int32_t>(std::clamp<int64_t>(dp_margin(&m[x * levels], levels, d[x]),
                                                      std::numeric_limits<int32_t>::min(),
                                                      std::numeric_limits<int32_t>::max()));
}

// The trellis margins (sm_dp_margin.hpp) of every pixel's level in the streamed dense words,
// from the frame's aggregated costs and its rows' occlusion penalties, into f.margin (both
// passes' min-marginals) and f.margin_fwd (the forward pass alone).
void trellis_margins(const PipelineResult& r, const Regs& regs, const OutImage& words, Frame& f) {
  const int w = r.agg.w, h = r.agg.h;
  f.margin.create(h, w, CV_32S);
  f.margin_fwd.create(h, w, CV_32S);
  std::vector<uint8_t> pen;
  std::vector<int> d(static_cast<size_t>(w));
  for (int y = 0; y < h; ++y) {
    edge_penalties(&r.rl.px[static_cast<size_t>(y) * w], w, regs.occ, regs.occ_edge, regs.edge_t, pen);
    const LineMargins m = dp_line_margins(r.agg.pix(0, y), w, pen.data(), f.levels);
    for (int x = 0; x < w; ++x)
      d[static_cast<size_t>(x)] =
          std::clamp((static_cast<int>(out_q4(words.px[static_cast<size_t>(y) * w + x])) + 8) >> 4, 0, f.levels - 1);
    row_margins(m.min_marginal, d, f.levels, f.margin.ptr<int32_t>(y));
    row_margins(m.forward_excess, d, f.levels, f.margin_fwd.ptr<int32_t>(y));
  }
}

// margins: also the trellis margins (keeps the frame's cost volumes while it runs).
Frame run_scene(const std::string& dir, int levels, bool margins) {
  const Scene s = load_scene(dir);
  Frame f;
  f.name = std::filesystem::path(dir).filename().string();
  f.levels = levels ? levels : std::min(254, (s.levels + 1) / 2 * 2);  // 0: as sm_evaluate --levels 0
  HwConfig hw;
  hw.disp = f.levels;
  hw.max_width = s.left.cols;
  hw.max_height = s.left.rows;
  Regs regs = Regs::defaults(hw);
  regs.filter_enable = 15;
  auto r = run_pipeline(to_image8(s.left), to_image8(s.right), hw, regs, margins);
  if (margins) {
    const OutputRegs dense = dense_mode(OutputRegs{});
    f.dense_raw = make_output(r.evidence, r.post, f.levels, dense, 0);
    f.dense_stream = smooth_output(f.dense_raw, dense.smooth_en, dense.smooth_t);
    trellis_margins(r, regs, f.dense_stream, f);
  }
  f.ev = std::move(r.evidence);
  f.post = std::move(r.post);
  f.left = s.left;
  f.gt = s.gt;
  f.mask = s.nonocc;
  return f;
}

// Means over the frames of one configuration.
struct Row {
  double b05 = 0, b1 = 0, b2 = 0, mae = 0, dens = 0, b1v = 0, b1_classic = 0, auc = 0, oauc = 0, ratio = 0;
};
// Adds one frame's figures to the sums of a Row (score and score_speckle divide them).
void add_frame(Row& m, const DispMetrics& d) {
  m.b05 += d.pct(d.bad05);
  m.b1 += d.pct(d.bad1);
  m.b2 += d.pct(d.bad2);
  m.mae += d.mae();
  m.dens += d.density();
  m.b1v += d.bad1_of_valid();
}

Row score(const std::vector<Frame>& fr, const OutputRegs& r, int conf_variant, bool sparsify) {
  Row m;
  int nc = 0;
  for (const auto& f : fr) {
    const OutImage o = make_output(f.ev, f.post, f.levels, r, conf_variant);
    const cv::Mat e = out_to_float(o);
    const DispMetrics d = disp_metrics(e, f.gt, f.mask);
    add_frame(m, d);
    if (classic(f.name)) m.b1_classic += d.pct(d.bad1), ++nc;
    if (sparsify) {
      const Sparsification s = sparsification(e, out_to_conf(o), f.gt, f.mask);
      m.auc += s.auc;
      m.oauc += s.oracle_auc;
      m.ratio += s.oracle_auc > 0 ? s.auc / s.oracle_auc : 0;
    }
  }
  const double n = static_cast<double>(fr.size());
  for (double* v : {&m.b05, &m.b1, &m.b2, &m.mae, &m.dens, &m.b1v, &m.auc, &m.oauc, &m.ratio}) *v /= n;
  m.b1_classic = nc ? m.b1_classic / nc : std::nan("");  // no classic scene: printed "-"
  return m;
}

void print_row(const std::string& name, const Row& m, bool sparsify) {
  const std::string cl4 = std::isnan(m.b1_classic) ? "-" : fmt::format("{:.2f}", m.b1_classic);
  fmt::print("| {:<44} | {:6.2f} | {:6.2f} | {:6.2f} | {:5.3f} | {:>6} | {:6.2f} | {:6.2f} |", name, m.b05, m.b1, m.b2,
             m.mae, cl4, m.dens, m.b1v);
  if (sparsify) fmt::print(" {:6.3f} | {:6.3f} | {:5.2f} | {:5.2f} |", m.auc, m.oauc, m.auc / m.oauc, m.ratio);
  fmt::print("\n");
}

void header(bool sparsify) {
  fmt::print("\n| {:<44} | bad0.5 | bad1.0 | bad2.0 |  MAE  | b1 cl4 | dens % | b1 val |", "configuration");
  if (sparsify) fmt::print("  AUC   | oracle | ratio | mean ratio |");
  fmt::print("\n|{:-<46}|--------|--------|--------|-------|--------|--------|--------|", "");
  if (sparsify) fmt::print("--------|--------|-------|-------|");
  fmt::print("\n");
}

void study_subpix(const std::vector<Frame>& fr) {
  header(false);
  OutputRegs off = dense_mode(OutputRegs{});
  off.fill_bg = 0;
  off.subpix_en = 0;
  print_row("integer (post, today's output)", score(fr, off, 0, false), false);
  const char* src[] = {"DP level (per-level storage)", "WTA fraction if |d-wta|<=1", "WTA band +-2 at DP level"};
  const char* fit[] = {"parabola", "equiangular"};
  for (int fb = 0; fb <= 1; ++fb)
    for (int s = 0; s < 3; ++s)
      for (int f = 0; f < 2; ++f) {
        OutputRegs r = off;
        r.subpix_en = 1;
        r.subpix_src = static_cast<uint8_t>(s);
        r.subpix_fit = static_cast<uint8_t>(f);
        r.fill_bg = static_cast<uint8_t>(fb);
        print_row(fmt::format("{}, {}{}", src[s], fit[f], fb ? ", bg fill" : ""), score(fr, r, 0, false), false);
      }
}

void study_valid(const std::vector<Frame>& fr) {
  header(false);
  // occ_en always on in the checked mode: without it the DP's fill paints phantom bars
  for (int lr = -1; lr <= 4; ++lr)
    for (int agree = -1; agree <= 4; ++agree)
      for (int uniq = 0; uniq <= 1; ++uniq) {
        OutputRegs r;
        r.lr_en = lr >= 0;
        r.lr_t = static_cast<uint8_t>(std::max(lr, 0));
        r.agree_en = agree >= 0;
        r.agree_t = static_cast<uint8_t>(std::max(agree, 0));
        r.uniq_en = uniq > 0;
        r.uniq_t = static_cast<uint8_t>(uniq);
        auto t = [](int v) { return v < 0 ? std::string("off") : std::to_string(v); };
        print_row(fmt::format("occ on, lr {} agree {} uniq {}", t(lr), t(agree), uniq ? t(uniq) : "off"),
                  score(fr, r, 0, false), false);
      }
  for (int occ_t = 1; occ_t <= 3; ++occ_t)
    for (int lr = 1; lr <= 3; ++lr) {
      OutputRegs r;
      r.occ_t = static_cast<uint8_t>(occ_t);
      r.lr_t = static_cast<uint8_t>(lr);
      print_row(fmt::format("defaults + occ_t {} lr {}", occ_t, lr), score(fr, r, 0, false), false);
    }
  for (int tex = 2; tex <= 8; tex += 2) {
    OutputRegs r;
    r.tex_en = 1;
    r.tex_t = static_cast<uint8_t>(tex);
    print_row(fmt::format("defaults + tex {}", tex), score(fr, r, 0, false), false);
  }
  OutputRegs fill = dense_mode(OutputRegs{});
  fill.fill_bg = 1;
  print_row("every rule off, background fill", score(fr, fill, 0, false), false);
}

// The forest of sm_output_bound.hpp on the dense output: what any validity rule or
// confidence computed from this evidence (and more) could reach.
void study_bound(const std::vector<Frame>& fr) {
  std::vector<cv::Mat> est;
  for (const auto& f : fr)
    est.push_back(out_to_float(make_output(f.ev, f.post, f.levels, dense_mode(OutputRegs{}), 0)));
  for (const bool evidence_only : {true, false}) {
    BoundConfig cfg;
    cfg.evidence_only = evidence_only;
    const auto& names = bound_feature_names();
    fmt::print("\nRandom forest, leave one scene out, features:");
    for (size_t k = 0; k < (evidence_only ? kEvidenceFeatures : names.size()); ++k) fmt::print(" {};", names[k]);
    fmt::print("\n");
    print_bound(fr, est, loso_scores(fr, est, cfg));
  }
}

// Where the speckle check reads the words' Q.4 values: before the smoothing (docs/algorithm.md
// 9.7), where a check in the IP would sit beside the object labeller, which reads them
// there too; or after it, the stream a host receives ("stream", or "raw" with SMOOTH_EN 0).
enum class SpeckleAt { kBeforeSmoothing, kOnStream };

// The words' Q.4 values as the speckle checks read them: CV_16S, invalid pixels negative.
cv::Mat words_q4(const OutImage& o) {
  cv::Mat q4;
  out_to_float(o).convertTo(q4, CV_16S, 16.0);
  return q4;
}

// A speckle check: the pixels it keeps (CV_8U) of a Q.4 map (CV_16S, negative = invalid).
using SpeckleCheck = std::function<cv::Mat(const cv::Mat& q4)>;

// The ideal check of sm_speckle.hpp; none when max_size is 0.
SpeckleCheck ideal_check(int max_size, int max_diff, int delay_rows) {
  if (max_size <= 0) return nullptr;
  return [=](const cv::Mat& q4) { return speckle_keep(q4, max_size, max_diff, delay_rows); };
}

// The stream's words under the rules of r with speckles made invalid by `check`.
OutImage study_words(const Frame& f, const OutputRegs& r, const SpeckleCheck& check, SpeckleAt at) {
  OutImage words = make_output(f.ev, f.post, f.levels, r, 0);
  auto apply = [&](OutImage& o) {
    if (!check) return;
    const cv::Mat keep = check(words_q4(o));
    for (int y = 0; y < o.h; ++y)
      for (int x = 0; x < o.w; ++x)
        if (out_valid(o.at(x, y)) && !keep.at<uint8_t>(y, x)) o.at(x, y) = 0;  // (no rule bit: a study)
  };
  if (at == SpeckleAt::kBeforeSmoothing) apply(words);
  words = smooth_output(words, r.smooth_en, r.smooth_t);
  if (at == SpeckleAt::kOnStream) apply(words);
  return words;
}

Row score_speckle(const std::vector<Frame>& fr, const OutputRegs& r, const SpeckleCheck& check, SpeckleAt at) {
  Row m;
  for (const auto& f : fr) add_frame(m, disp_metrics(out_to_float(study_words(f, r, check, at)), f.gt, f.mask));
  const double n = static_cast<double>(fr.size());
  for (double* v : {&m.b05, &m.b1, &m.b2, &m.mae, &m.dens, &m.b1v}) *v /= n;
  return m;
}

// The check with a bounded label table (sm_speckle_table.hpp) against the ideal streaming
// one, at the chosen S and D, occlusion rule only, before the smoothing.
void print_speckle_table(const std::vector<Frame>& fr) {
  OutputRegs r;
  r.lr_en = r.agree_en = 0;
  fmt::print("\nWith a label table (occlusion rule only, S 1000, D 8, words before the smoothing):\n\n");
  fmt::print("| {:<22} | {:>5} | dens % | b1 val | {:>11} | {:>12} | {:>11} |\n", "form", "K", "peak labels",
             "longest find", "KEEP pixels");
  fmt::print("|{:-<24}|-------|--------|--------|-------------|--------------|-------------|\n", "");
  for (const int k : {32, 16}) {
    const Row ideal = score_speckle(fr, r, ideal_check(1000, 8, k), SpeckleAt::kBeforeSmoothing);
    fmt::print("| {:<22} | {:>5} | {:6.2f} | {:6.2f} | {:>11} | {:>12} | {:>11} |\n", "ideal (sm_speckle)", k,
               ideal.dens, ideal.b1v, "", "", "");
    for (const int labels : {1024, 512, 256}) {
      SpeckleStats most;  // over the scenes
      const SpeckleCheck table = [&](const cv::Mat& q4) {
        SpeckleStats st;
        cv::Mat keep = speckle_keep_table(q4, 1000, 8, k, labels, &st);
        most.peak_labels = std::max(most.peak_labels, st.peak_labels);
        most.longest_find = std::max(most.longest_find, st.longest_find);
        most.keep_pixels += st.keep_pixels;
        return keep;
      };
      const Row m = score_speckle(fr, r, table, SpeckleAt::kBeforeSmoothing);
      fmt::print("| {:<22} | {:>5} | {:6.2f} | {:6.2f} | {:>11} | {:>12} | {:>11} |\n",
                 fmt::format("table of {} labels", labels), k, m.dens, m.b1v, most.peak_labels, most.longest_find,
                 most.keep_pixels);
    }
  }
}

// What a streaming check in the IP would hold at once (sm_speckle.hpp, SpeckleHold), per
// scene, on the words before the smoothing at the rules the check replaces (occlusion only)
// and half a pixel, for 32 and 16 rows of look-ahead.
void print_speckle_hold(const std::vector<Frame>& fr) {
  OutputRegs r;
  r.lr_en = r.agree_en = 0;
  fmt::print("\nHeld at once by a streaming check (occlusion rule only, D 8, words before the smoothing):\n\n");
  fmt::print("| {:<12} | {:>9} | {:>16} | {:>15} | {:>16} | {:>15} |\n", "scene", "size", "K 32: regions",
             "K 32: labels", "K 16: regions", "K 16: labels");
  fmt::print(
      "|--------------|-----------|------------------|-----------------|------------------|-----------------|\n");
  SpeckleHold most32, most16;
  for (const auto& f : fr) {
    const cv::Mat q4 = words_q4(make_output(f.ev, f.post, f.levels, r, 0));
    const SpeckleHold k32 = speckle_hold(q4, 8, 32), k16 = speckle_hold(q4, 8, 16);
    fmt::print("| {:<12} | {:>9} | {:>16} | {:>15} | {:>16} | {:>15} |\n", f.name,
               fmt::format("{}x{}", q4.cols, q4.rows), k32.regions, k32.labels, k16.regions, k16.labels);
    most32 = {std::max(most32.regions, k32.regions), std::max(most32.labels, k32.labels)};
    most16 = {std::max(most16.regions, k16.regions), std::max(most16.labels, k16.labels)};
  }
  fmt::print("| {:<12} | {:>9} | {:>16} | {:>15} | {:>16} | {:>15} |\n", "most", "", most32.regions, most32.labels,
             most16.regions, most16.labels);
}

// Checked-mode density against bad-1.0 of the valid pixels with a speckle check after the
// rules: regions of at most S pixels (4-neighbours within D/16 px) become invalid, decided
// on the whole frame or, as a streaming core would, K rows after the row.
void study_speckle(const std::vector<Frame>& fr) {
  struct Rules {
    const char* name;
    int occ_t, lr, agree;  // -1: rule off
  };
  const Rules rules[] = {{"defaults (occ 1, lr 2, agree 2)", 1, 2, 2},
                         {"occ 1 only", 1, -1, -1},
                         {"occ 2 only", 2, -1, -1},
                         {"occ 1, lr 4", 1, 4, -1},
                         {"occ 1, agree 4", 1, -1, 4}};
  fmt::print("\n| {:<32} | {:<8} | {:>5} | {:>3} | {:>5} | dens % | b1 val | bad1.0 |  MAE  |\n", "rules", "reads", "S",
             "D", "K");
  fmt::print("|{:-<34}|----------|-------|-----|-------|--------|--------|--------|-------|\n", "");
  for (const auto& ru : rules) {
    OutputRegs r;
    r.occ_t = static_cast<uint8_t>(ru.occ_t);
    r.lr_en = ru.lr >= 0;
    r.lr_t = static_cast<uint8_t>(std::max(ru.lr, 0));
    r.agree_en = ru.agree >= 0;
    r.agree_t = static_cast<uint8_t>(std::max(ru.agree, 0));
    OutputRegs raw = r;  // the stream with SMOOTH_EN 0
    raw.smooth_en = 0;
    auto row = [&](const OutputRegs& regs, int s, int d, int k, SpeckleAt at) {
      const Row m = score_speckle(fr, regs, ideal_check(s, d, k), at);
      const std::string ks = k >= 1 << 15 ? "frame" : std::to_string(k);
      const char* reads = at == SpeckleAt::kBeforeSmoothing ? "words" : regs.smooth_en ? "stream" : "raw";
      fmt::print("| {:<32} | {:<8} | {:>5} | {:>3} | {:>5} | {:6.2f} | {:6.2f} | {:6.2f} | {:5.3f} |\n", ru.name, reads,
                 s, d, ks, m.dens, m.b1v, m.b1, m.mae);
    };
    row(r, 0, 0, 0, SpeckleAt::kOnStream);
    for (const int s : {300, 1000, 2000})
      for (const int d : {8, 16}) {
        for (const int k : {1 << 15, 32, 16, 8}) row(r, s, d, k, SpeckleAt::kBeforeSmoothing);
        row(r, s, d, 1 << 15, SpeckleAt::kOnStream);
        row(raw, s, d, 1 << 15, SpeckleAt::kOnStream);
      }
  }
  print_speckle_hold(fr);
  print_speckle_table(fr);
}

// The streamed words with the confidence halved where the speckle stage (sr, rows) would
// clear the pixel; raw: the words the stage sees (before the smoothing).
OutImage halve_speckles(OutImage streamed, const OutImage& raw, const SpeckleRegs& sr, int rows) {
  const OutImage cleared = speckle_output(raw, sr, rows, HwConfig{}.speckle_labels);
  for (size_t i = 0; i < streamed.px.size(); ++i)
    if (cleared.px[i] == kOutSpeckle)
      streamed.px[i] = make_out_word(true, out_conf(streamed.px[i]) / 2, out_q4(streamed.px[i]));
  return streamed;
}

// The dense stream's confidence with the speckle stage's verdict (9.8, on the dense words
// before the smoothing, zynq's 1,024 labels) as one more cue: the confidence of every
// pixel the stage would clear is halved. Size 0: the confidence as streamed.
void study_speckle_conf(const std::vector<Frame>& fr) {
  struct Case {
    int size, trust, diff, rows;
  };
  const Case cases[] = {{0, 0, 0, 0},        {1000, 100, 8, 32},  {500, 100, 8, 32},  {2000, 100, 8, 32},
                        {4000, 100, 8, 32},  {1000, 4095, 8, 32}, {1000, 100, 4, 32}, {1000, 100, 12, 32},
                        {1000, 100, 16, 32}, {1000, 100, 8, 16},  {1000, 100, 8, 62}};
  // each frame's dense words before the smoothing (the stage's input) and as streamed, once
  const OutputRegs dense = dense_mode(OutputRegs{});
  std::vector<OutImage> raw, streamed;
  for (const auto& f : fr) {
    raw.push_back(make_output(f.ev, f.post, f.levels, dense, 0));
    streamed.push_back(smooth_output(raw.back(), dense.smooth_en, dense.smooth_t));
  }
  fmt::print("\nDense confidence, halved where the speckle stage would clear the pixel:\n\n");
  fmt::print("| {:>5} | {:>5} | {:>4} | {:>4} |  AUC   | oracle | ratio |\n", "size", "trust", "diff", "rows");
  fmt::print("|-------|-------|------|------|--------|--------|-------|\n");
  for (const Case& c : cases) {
    double auc = 0, oracle = 0;
    for (size_t k = 0; k < fr.size(); ++k) {
      const Frame& f = fr[k];
      const SpeckleRegs sr{1, static_cast<uint16_t>(c.size), static_cast<uint8_t>(c.diff),
                           static_cast<uint16_t>(c.trust)};
      const OutImage o = c.size > 0 ? halve_speckles(streamed[k], raw[k], sr, c.rows) : streamed[k];
      const Sparsification sp = sparsification(out_to_float(o), out_to_conf(o), f.gt, f.mask);
      auc += sp.auc;
      oracle += sp.oracle_auc;
    }
    fmt::print("| {:>5} | {:>5} | {:>4} | {:>4} | {:6.3f} | {:6.3f} | {:5.2f} |\n", c.size, c.trust, c.diff, c.rows,
               auc / static_cast<double>(fr.size()), oracle / static_cast<double>(fr.size()), auc / oracle);
  }
}

// Weights of a confidence from the evidence byte's three flags and ratio (9.3), the
// smoothing window's support counts K and K8 (9.7) and wider supports (sm_window_support.hpp):
// the row's samples R and the ring of samples 10 rows and columns away S (or its rows at and
// above the pixel's), saturated to 8 bits. after_smoothing: the stream's confidence as it is
// plus `row` times R counted on the smoothed words (a stage after the smoothing's, which
// sees only the stream; the other weights unused).
struct SupportWeights {
  const char* name;
  int flag, ratio, k, k8, row, ring;
  bool above_only, after_smoothing;
};

// One frame's supports, each per pixel of its dense words before the smoothing.
struct Supports {
  std::vector<uint16_t> k, k8, row, ring, ring_above, row_streamed;
};

Supports frame_supports(const OutImage& raw, const OutImage& streamed, int smooth_t) {
  std::vector<Offset> win;
  for (int dy = -kSmoothR; dy <= kSmoothR; ++dy)
    for (int dx = -kSmoothR; dx <= kSmoothR; ++dx) win.push_back({dy, dx});
  return {offset_support(raw, win, smooth_t),
          offset_support(raw, win, kSupportNear),
          offset_support(raw, row_offsets(15, 3), 16),
          offset_support(raw, ring_offsets(10, false), 16),
          offset_support(raw, ring_offsets(10, true), 16),
          offset_support(streamed, row_offsets(15, 3), 16)};
}

// The streamed words with their confidence replaced by the weights' score.
OutImage support_scored(const OutImage& streamed, const OutImage& raw, const Supports& s, const SupportWeights& w) {
  OutImage o = streamed;
  for (size_t i = 0; i < o.px.size(); ++i) {
    if (!out_valid(o.px[i])) continue;
    if (w.after_smoothing) {
      const int sum = static_cast<int>(out_conf(o.px[i])) + w.row * s.row_streamed[i];
      o.px[i] = make_out_word(true, static_cast<unsigned>(std::min(sum, 255)), out_q4(o.px[i]));
      continue;
    }
    const unsigned e = out_conf(raw.px[i]);
    const int flags = static_cast<int>((e >> 7 & 1) + (e >> 6 & 1) + (e >> 5 & 1));
    const int sum = w.flag * flags + w.ratio * static_cast<int>(e & 31) + w.k * s.k[i] + w.k8 * s.k8[i] +
                    w.row * s.row[i] + w.ring * (w.above_only ? s.ring_above[i] : s.ring[i]);
    o.px[i] = make_out_word(true, static_cast<unsigned>(std::min(sum, 255)), out_q4(o.px[i]));
  }
  return o;
}

// The dense confidence with wider supports than the smoothing window's: AUC over the
// oracle's, 14-scene means, as streamed and halved where zynq's speckle stage would clear
// the pixel. The first row's weights are the smoothing's own and the last row's the stream's,
// smoothing and row support (both checked word for word).
void study_window_conf(const std::vector<Frame>& fr) {
  const SupportWeights cases[] = {{"the smoothing's confidence", 16, 1, 3, 2, 0, 0, false, false},
                                  {"+ row", 12, 1, 2, 1, 4, 0, false, false},
                                  {"+ row + ring above", 16, 1, 2, 1, 4, 4, true, false},
                                  {"+ row + ring", 16, 1, 2, 1, 3, 4, false, false},
                                  {"+ ring", 16, 1, 2, 1, 0, 6, false, false},
                                  {"c + 4 row, after the smoothing", 0, 0, 0, 0, 4, 0, false, true},
                                  {"c + 5 row: the stream (9.7)", 0, 0, 0, 0, 5, 0, false, true}};
  const OutputRegs dense = dense_mode(OutputRegs{});
  SpeckleRegs sr;
  sr.en = 1;
  std::vector<OutImage> raw, streamed;
  std::vector<Supports> sup;
  for (const Frame& f : fr) {
    raw.push_back(make_output(f.ev, f.post, f.levels, dense, 0));
    streamed.push_back(smooth_output(raw.back(), dense.smooth_en, dense.smooth_t));
    sup.push_back(frame_supports(raw.back(), streamed.back(), dense.smooth_t));
    if (support_scored(streamed.back(), raw.back(), sup.back(), cases[0]).px != streamed.back().px)
      throw ToolError("window-conf: the smoothing's weights do not give the smoothing's confidence");
    if (support_scored(streamed.back(), raw.back(), sup.back(), cases[6]).px != row_support_output(streamed.back()).px)
      throw ToolError("window-conf: the row support's weights do not give the stream's confidence");
  }
  fmt::print(
      "\nDense confidence with wider supports (R: row samples at +-3 .. +-15 step 3; S: the ring at 10),\n"
      "score min(255, flags + ratio + K + K8 + R + S weighted), AUC / oracle:\n\n");
  fmt::print("| {:<30} | flag | ratio | K | K8 | R | S | S rows | as streamed | halved on speckles |\n", "score");
  fmt::print("|{:-<32}|------|-------|---|----|---|---|--------|------------:|-------------------:|\n", "");
  for (const SupportWeights& w : cases) {
    double auc = 0, oracle = 0, auc_sp = 0, oracle_sp = 0;
    for (size_t k = 0; k < fr.size(); ++k) {
      const OutImage o = support_scored(streamed[k], raw[k], sup[k], w);
      const cv::Mat est = out_to_float(o);
      const Sparsification sp = sparsification(est, out_to_conf(o), fr[k].gt, fr[k].mask);
      const Sparsification sh = sparsification(
          est, out_to_conf(halve_speckles(o, raw[k], sr, named_config("zynq").speckle_rows)), fr[k].gt, fr[k].mask);
      auc += sp.auc, oracle += sp.oracle_auc, auc_sp += sh.auc, oracle_sp += sh.oracle_auc;
    }
    fmt::print("| {:<30} | {:>4} | {:>5} | {} | {:>2} | {} | {} | {:<6} | {:11.2f} | {:18.2f} |\n", w.name, w.flag,
               w.ratio, w.k, w.k8, w.row, w.ring,
               !w.ring        ? ""
               : w.above_only ? "above"
                              : "both",
               auc / oracle, auc_sp / oracle_sp);
  }
}

// The streamed dense confidence c with the trellis margin m added: a c + clamp(m, lo, hi),
// saturated to 8 bits (a 0: the margin alone; hi 0: c alone); also with c halved where
// zynq's speckle stage, enabled at its registers' resets, would clear the pixel; m from both
// passes, then from the forward pass alone. The frames are run_scene's with the margins (and
// so with their dense words).
void study_dp_margin(const std::vector<Frame>& fr) {
  struct Case {
    double a;
    int lo, hi;
  };
  const Case cases[] = {{1, 0, 0},      {0, -255, 255},  {0.5, 0, 20}, {0.5, 0, 40}, {0.5, 0, 60},
                        {0.5, -20, 40}, {0.5, -255, 40}, {1, 0, 40},   {1, -20, 60}};
  SpeckleRegs sr;
  sr.en = 1;
  std::vector<cv::Mat> est, conf, conf_sp;  // each frame's streamed dense words (run_scene's)
  for (const Frame& f : fr) {
    est.push_back(out_to_float(f.dense_stream));
    conf.push_back(out_to_conf(f.dense_stream));
    conf_sp.push_back(out_to_conf(halve_speckles(f.dense_stream, f.dense_raw, sr, named_config("zynq").speckle_rows)));
  }
  // The AUC over the oracle's, 14-scene means, of one case over the confidences c.
  auto ratio = [&](const Case& c, const std::vector<cv::Mat>& cs, cv::Mat Frame::*m) {
    double auc = 0, oracle = 0;
    for (size_t k = 0; k < fr.size(); ++k) {
      cv::Mat score(cs[k].size(), CV_8U);
      for (int y = 0; y < score.rows; ++y)
        for (int x = 0; x < score.cols; ++x)
          score.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(c.a * cs[k].at<uint8_t>(y, x) +
                                                               std::clamp((fr[k].*m).at<int32_t>(y, x), c.lo, c.hi));
      const Sparsification sp = sparsification(est[k], score, fr[k].gt, fr[k].mask);
      auc += sp.auc;
      oracle += sp.oracle_auc;
    }
    return auc / oracle;
  };
  fmt::print(
      "\nDense confidence c plus the trellis margin m, AUC / oracle (m from both passes; from the forward "
      "pass alone):\n\n");
  fmt::print("| score                      | c as streamed | c halved on speckles | forward: as streamed | halved |\n");
  fmt::print("|----------------------------|--------------:|---------------------:|---------------------:|-------:|\n");
  for (const Case& c : cases) {
    const std::string name = c.hi == 0  ? "c"
                             : c.a == 0 ? fmt::format("clamp(m, {}, {})", c.lo, c.hi)
                                        : fmt::format("{} c + clamp(m, {}, {})", c.a, c.lo, c.hi);
    fmt::print("| {:<26} | {:13.2f} | {:20.2f} | {:20.2f} | {:6.2f} |\n", name, ratio(c, conf, &Frame::margin),
               ratio(c, conf_sp, &Frame::margin), ratio(c, conf, &Frame::margin_fwd),
               ratio(c, conf_sp, &Frame::margin_fwd));
  }
}

void study_conf(const std::vector<Frame>& fr) {
  header(true);
  for (int v = 0; v < kConfidenceVariants; ++v)
    print_row(fmt::format("dense, confidence variant {}", v), score(fr, dense_mode(OutputRegs{}), v, true), true);
}

// Every pixel's evidence, output levels and ground truth as int16 columns (x y d matched cm
// c0 cp dw c1 c2 cmax fill_bg post_d gt*16 b0..b4 lr gap evaluated dense*16 checked*16
// confidence; outputs -16 where invalid), for offline analysis of windows around a pixel.
void dump_features(const std::vector<Frame>& fr, const std::string& dir) {
  OutputSet out;  // all scenes' files or none
  for (const auto& f : fr) {
    std::vector<int16_t> v;
    const auto& e = f.ev;
    const OutImage dense = make_output(f.ev, f.post, f.levels, dense_mode(OutputRegs{}), 0);
    const cv::Mat dq = out_to_float(dense), conf = out_to_conf(dense);
    const cv::Mat cq = out_to_float(make_output(f.ev, f.post, f.levels, OutputRegs{}, 0));
    for (int y = 0; y < f.post.h; ++y)
      for (int x = 0; x < f.post.w; ++x) {
        const float g = f.gt.at<float>(y, x);
        const int cols[] = {x,
                            y,
                            e.d.at(x, y),
                            e.matched.at(x, y),
                            e.cm.at(x, y),
                            e.c0.at(x, y),
                            e.cp.at(x, y),
                            e.dw.at(x, y),
                            e.c1.at(x, y),
                            e.c2.at(x, y),
                            e.cmax.at(x, y),
                            e.fill_bg.at(x, y),
                            static_cast<int>(disp_value(f.post.at(x, y))),
                            static_cast<int>(std::lround(g * 16)),
                            e.band[0].at(x, y),
                            e.band[1].at(x, y),
                            e.band[2].at(x, y),
                            e.band[3].at(x, y),
                            e.band[4].at(x, y),
                            e.lr.at(x, y),
                            e.gap.at(x, y),
                            evaluated(f.gt, f.mask, y, x),
                            static_cast<int>(std::lround(dq.at<float>(y, x) * 16)),
                            static_cast<int>(std::lround(cq.at<float>(y, x) * 16)),
                            conf.at<uint8_t>(y, x)};
        for (int c : cols) v.push_back(static_cast<int16_t>(c));
      }
    out.write((std::filesystem::path(dir) / (f.name + ".bin")).string(),
              [&](const std::string& tmp) {
                write_text_atomic(tmp,
                                  std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(int16_t)));
              },
              true);
  }
  out.commit();
}

// The dataset's scene folders, only those named in `names` when it is not empty (each
// name must be a scene of the dataset).
std::vector<std::string> selected_scenes(const std::string& dataset, const std::vector<std::string>& names) {
  std::vector<std::string> dirs, found;
  for (const auto& d : list_scenes(dataset)) {
    const std::string n = std::filesystem::path(d).filename().string();
    if (!names.empty() && std::find(names.begin(), names.end(), n) == names.end()) continue;
    dirs.push_back(d);
    found.push_back(n);
  }
  for (const auto& n : names)
    if (std::find(found.begin(), found.end(), n) == found.end())
      throw ToolError(fmt::format("--scenes: {}: not a scene of {}", n, dataset));
  if (dirs.empty()) throw ToolError(fmt::format("{}: no scenes", dataset));
  return dirs;
}

int run(int argc, char** argv) {
  CLI::App app{"Score the output stage's sub-pixel estimators, validity rules and confidence on a dataset"};
  std::string dataset;
  std::vector<std::string> scenes, studies{"subpix", "valid", "conf"};
  app.add_option("dataset", dataset, "dataset folder (../shared/datasets layout)")->required();
  app.add_option("--scenes", scenes, "comma-separated scene names (default: all)")->delimiter(',');
  std::string dump_dir;
  int levels = HwConfig{}.disp;
  app.add_option("--levels", levels, "disparity levels, even, 4..254 (0: per scene, as sm_evaluate --levels 0)")
      ->capture_default_str();
  app.add_option("--dump-features", dump_dir, "write <scene>.bin (int16 columns, see dump_features) here");
  app.add_option("--study", studies,
                 "comma-separated subset of subpix,valid,conf,bound,speckle,speckle-conf,dp-margin,window-conf "
                 "(bound: a random forest on the evidence, leave one scene out, ~3 min; speckle: the rules then a "
                 "speckle check; speckle-conf: the speckle stage's verdict in the confidence; dp-margin: the "
                 "trellis's min-marginals in the confidence; window-conf: wider supports in the confidence; none "
                 "of these five is in the default set)")
      ->delimiter(',')
      ->check(
          CLI::IsMember({"subpix", "valid", "conf", "bound", "speckle", "speckle-conf", "dp-margin", "window-conf"}));
  if (const auto rc = parse_args(app, argc, argv)) return *rc;
  check_levels("--levels", levels, true);
  if (!dump_dir.empty()) check_output_folder("--dump-features", dump_dir);
  quiet_opencv();
  const auto dirs = selected_scenes(dataset, scenes);
  const bool margins = std::find(studies.begin(), studies.end(), "dp-margin") != studies.end();
  if (dirs.size() < 2 && std::find(studies.begin(), studies.end(), "bound") != studies.end())
    throw ToolError("--study bound: needs two scenes or more (each is scored by a forest trained on the others)");
  std::vector<Frame> fr;
  for (const auto& d : dirs) {
    fmt::print(stderr, "sm_output_study: {} ...\n", std::filesystem::path(d).filename().string());
    fr.push_back(run_scene(d, levels, margins));
  }
  if (!dump_dir.empty()) dump_features(fr, dump_dir);
  fmt::print("{} scenes; means over all of them (b1 cl4: bad-1.0 of the classic four)\n", fr.size());
  for (const auto& s : studies) {
    if (s == "subpix")
      study_subpix(fr);
    else if (s == "valid")
      study_valid(fr);
    else if (s == "conf")
      study_conf(fr);
    else if (s == "speckle")
      study_speckle(fr);
    else if (s == "speckle-conf")
      study_speckle_conf(fr);
    else if (s == "dp-margin")
      study_dp_margin(fr);
    else if (s == "window-conf")
      study_window_conf(fr);
    else
      study_bound(fr);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return guarded_main("sm_output_study", run, argc, argv); }
