// Streak study (issue 21, docs/evaluation.md "Streak study"): runs the reference model on
// every scene of a stereo dataset and scores, with the same bad-1.0 and streak measure as
// sm_evaluate (sm::tools::bad1 / sm::tools::streaks), the current post-processing chain
// against candidates that target horizontal streaks:
//   - post filters a streaming 1-pixel-per-clock RTL can do with a few line buffers
//     (longer / run-gated / intensity-guided vertical medians, vertical-consistency
//     filters, recursive and run-based band filters), before or after the chain;
//   - an inter-scanline term in the DP: lambda * min(max(|d - d_prev(x)| - dz, 0), T) added
//     to every matched cost A(x, d) of row y, with d_prev = this DP's own output of row
//     y - back (back 1 = the ideal previous row, 2 = what sm_dp could feed, 3 = safe).
// Every candidate is judged on all scenes at once (means over the whole dataset).
//   sm_streak_study DATASET [--json out.json] [--groups rband,dp,...] [--detail NAME,...] [--dump DIR]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "dp.hpp"
#include "pipeline.hpp"
#include "post.hpp"

using namespace sm;
using namespace sm::tools;

namespace {

// Disparity as int, -1 = invalid.
int val(const DispImage& d, int x, int y) {
  const DispPix p = d.at(x, y);
  return disp_valid(p) ? static_cast<int>(disp_value(p)) : -1;
}
DispPix pix(int v) { return v < 0 ? DispPix{0} : make_disp(static_cast<unsigned>(v), true); }
bool differ(int a, int b) { return a >= 0 && b >= 0 && std::abs(a - b) > 1; }
bool agree(int a, int b) { return a >= 0 && b >= 0 && std::abs(a - b) <= 1; }

struct Ctx {
  const HwConfig& hw;
  const Image8& left;  // the left image the DP matched (after brightness / rectification)
};
using Filter = std::function<DispImage(const DispImage&, const Ctx&)>;

Filter med(int ry, int rx) {
  return [ry, rx](const DispImage& d, const Ctx& c) { return post_median(d, c.hw, ry, rx); };
}
const std::vector<Filter>& chain() {  // F1 vmed5 -> F2 med3x3 -> F3 med5x3 (the model's chain)
  static const std::vector<Filter> c = {med(2, 0), med(1, 1), med(2, 1)};
  return c;
}

// In each row, the cells of `cond` that lie in a run of set cells at least `len` long.
std::vector<uint8_t> runs_at_least(const std::vector<uint8_t>& cond, int w, int h, int len) {
  std::vector<uint8_t> out(cond.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w;) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (!cond[i]) {
        ++x;
        continue;
      }
      int e = x;
      while (e < w && cond[static_cast<size_t>(y) * w + e]) ++e;
      if (e - x >= len)
        for (int k = x; k < e; ++k) out[static_cast<size_t>(y) * w + k] = 1;
      x = e;
    }
  return out;
}

// Vertical median of 2R+1 rows where the centre row's run of equal disparity containing
// the pixel is at least L long, the 5x1 median (F1) elsewhere.
Filter vmed_run(int r, int l) {
  return [r, l](const DispImage& in, const Ctx& c) {
    const DispImage a = post_median(in, c.hw, r, 0), b = post_median(in, c.hw, 2, 0);
    DispImage out = b;
    for (int y = 0; y < in.h; ++y)
      for (int x = 0; x < in.w;) {
        int e = x;
        while (e < in.w && in.at(e, y) == in.at(x, y)) ++e;
        if (e - x >= l)
          for (int k = x; k < e; ++k) out.at(k, y) = a.at(k, y);
        x = e;
      }
    return out;
  };
}

// Intensity-guided vertical median of 2R+1 rows: a window row whose left-image intensity
// differs from the centre's by more than tau (or lies outside the frame) takes the
// centre's key, like the chain's border rule.
Filter gvmed(int r, int tau) {
  return [r, tau](const DispImage& in, const Ctx& c) {
    DispImage out(in.w, in.h);
    std::vector<int> k(static_cast<size_t>(2 * r + 1));
    for (int y = 0; y < in.h; ++y)
      for (int x = 0; x < in.w; ++x) {
        const int kc = val(in, x, y) + 1, ic = c.left.at(x, y);
        for (int j = -r; j <= r; ++j) {
          const int yy = y + j;
          const bool use = yy >= 0 && yy < in.h && std::abs(c.left.at(x, yy) - ic) <= tau;
          k[static_cast<size_t>(j + r)] = use ? val(in, x, yy) + 1 : kc;
        }
        std::nth_element(k.begin(), k.begin() + r, k.end());
        out.at(x, y) = pix(k[static_cast<size_t>(r)] - 1);
      }
    return out;
  };
}

// Vertical consistency (not recursive): pixel c at (x, y); du / dd = the nearest rows above
// / below within K whose disparity differs from c by more than 1 (the rows between are
// within 1 of c). When both exist, du + dd <= K + 1 (a band of at most K rows) and the two
// agree with each other (within 1) -- and, with tau >= 0, both have a left intensity within
// tau of the centre's -- the pixel is a band pixel, replacement min(above, below). A band
// pixel is replaced when it lies in a horizontal run of at least L band pixels.
// Window: K rows above and below (2K line buffers).
Filter vcons(int kmax, int l, int tau) {
  return [kmax, l, tau](const DispImage& in, const Ctx& c) {
    const int w = in.w, h = in.h;
    std::vector<uint8_t> cond(static_cast<size_t>(w) * h, 0);
    std::vector<int> rep(cond.size(), -1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int v = val(in, x, y);
        if (v < 0) continue;
        int du = 0, dd = 0;
        for (int k = 1; k <= kmax && y - k >= 0; ++k) {
          const int a = val(in, x, y - k);
          if (a < 0) break;
          if (std::abs(a - v) > 1) {
            du = k;
            break;
          }
        }
        for (int k = 1; k <= kmax && y + k < h; ++k) {
          const int b = val(in, x, y + k);
          if (b < 0) break;
          if (std::abs(b - v) > 1) {
            dd = k;
            break;
          }
        }
        if (!du || !dd || du + dd > kmax + 1) continue;
        const int a = val(in, x, y - du), b = val(in, x, y + dd);
        if (!agree(a, b)) continue;
        if (tau >= 0) {
          const int i = c.left.at(x, y);
          if (std::abs(c.left.at(x, y - du) - i) > tau || std::abs(c.left.at(x, y + dd) - i) > tau) continue;
        }
        const size_t i = static_cast<size_t>(y) * w + x;
        cond[i] = 1;
        rep[i] = std::min(a, b);
      }
    const auto keep = runs_at_least(cond, w, h, l);
    DispImage out = in;
    for (size_t i = 0; i < keep.size(); ++i)
      if (keep[i]) out.px[i] = pix(rep[i]);
    return out;
  };
}

// Recursive band filter, top to bottom: a = the filter's own output at (x, y-1). The input
// pixel c differs from a by more than 1 and within K rows below the input returns to a
// (some row y+k, 1 <= k <= K, within 1 of a), and -- with tau >= 0 -- the left intensity at
// (x, y) is within tau of that at (x, y-1): a band pixel, replacement a. Replaced when it
// lies in a horizontal run of at least L band pixels. `whole_run` (run-based variant):
// instead, per maximal run of equal input disparity in row y at least L long, when at least
// frac of its pixels are band pixels, every pixel of the run that differs from a (by more
// than 1) takes a. Line buffers: K rows of look-ahead + the output row above.
Filter rband(int kmax, int l, int tau, bool whole_run = false, double frac = 0.5) {
  return [=](const DispImage& in, const Ctx& c) {
    const int w = in.w, h = in.h;
    DispImage out = in;
    std::vector<uint8_t> cond(static_cast<size_t>(w)), keep;
    for (int y = 1; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const int v = val(in, x, y), a = val(out, x, y - 1);
        bool band = differ(v, a) && (tau < 0 || std::abs(c.left.at(x, y) - c.left.at(x, y - 1)) <= tau);
        if (band) {
          band = false;
          for (int k = 1; k <= kmax && y + k < h && !band; ++k) band = agree(val(in, x, y + k), a);
        }
        cond[static_cast<size_t>(x)] = band;
      }
      if (!whole_run) {
        keep = runs_at_least(cond, w, 1, l);
        for (int x = 0; x < w; ++x)
          if (keep[static_cast<size_t>(x)]) out.at(x, y) = out.at(x, y - 1);
        continue;
      }
      for (int x = 0; x < w;) {
        int e = x, n = 0;
        while (e < w && in.at(e, y) == in.at(x, y)) n += cond[static_cast<size_t>(e++)];
        if (e - x >= l && n >= frac * (e - x))
          for (int k = x; k < e; ++k)
            if (differ(val(in, k, y), val(out, k, y - 1))) out.at(k, y) = out.at(k, y - 1);
        x = e;
      }
    }
    return out;
  };
}

// DP with an inter-scanline term (see the header); lambda 0 = the model's trellis_dp.
struct DpSpec {
  int lambda = 0, t = 0, dz = 0, back = 0, scale = 1;
  // Edge-dependent occlusion penalty (model trellis_dp_edge, no inter-scanline term): occ
  // `eflat` away from intensity edges of the left image, `eedge` where |dI| > `ethr`;
  // eflat < 0: off.
  int eflat = -1, eedge = 0, ethr = 0;
  std::string key() const {
    if (eflat >= 0) return fmt::format("dpedge o{} e{} T{}", eflat, eedge, ethr);
    if (!lambda) return "dp";
    const std::string l = scale == 1 ? fmt::format("{}", lambda) : fmt::format("{}/{}", lambda, scale);
    return fmt::format("dp l{} T{} dz{} y-{}", l, t, dz, back);
  }
};

DispImage dp_vert(const CostVolume& agg, const Image8& left, uint8_t occ, const HwConfig& hw, const DpSpec& s) {
  if (s.eflat >= 0)
    return trellis_dp_edge(agg, left, static_cast<uint8_t>(s.eflat), static_cast<uint8_t>(s.eedge),
                           static_cast<uint8_t>(s.ethr), hw);
  const int w = agg.w, h = agg.h, nd = agg.d;
  DispImage out(w, h);
  DpScratch scratch;
  DpLine line;
  std::vector<uint8_t> a(static_cast<size_t>(w) * nd);
  for (int y = 0; y < h; ++y) {
    const uint8_t* src = agg.pix(0, y);
    if (s.lambda && y - s.back >= 0) {
      for (int x = 0; x < w; ++x) {
        const int dp = val(out, x, y - s.back);
        for (int d = 0; d < nd; ++d) {
          const size_t i = static_cast<size_t>(x) * nd + d;
          const int c = s.scale * src[i] + s.lambda * std::min(std::max(std::abs(d - dp) - s.dz, 0), s.t);
          if (c > 255) throw std::logic_error("dp_vert: cost above 8 bits");
          a[i] = static_cast<uint8_t>(c);
        }
      }
      src = a.data();
    } else if (s.scale != 1) {
      for (size_t i = 0; i < a.size(); ++i) {
        const int c = s.scale * agg.pix(0, y)[i];
        if (c > 255) throw std::logic_error("dp_vert: cost above 8 bits");
        a[i] = static_cast<uint8_t>(c);
      }
      src = a.data();
    }
    if (static_cast<int>(occ) * s.scale > 255) throw std::logic_error("dp_vert: occ above 8 bits");
    trellis_line(src, w, static_cast<uint8_t>(occ * s.scale), hw, scratch, line);
    std::copy(line.disp.begin(), line.disp.end(), &out.at(0, y));
  }
  return out;
}

struct Candidate {
  std::string group, name;
  DpSpec dp;
  std::vector<Filter> post;
};

std::vector<Filter> operator+(std::vector<Filter> a, const std::vector<Filter>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::string tau_name(int tau) { return tau < 0 ? "" : fmt::format(" t{}", tau); }

std::vector<Candidate> candidates() {
  std::vector<Candidate> c;
  const std::vector<Filter> f1 = {med(2, 0)}, f23 = {med(1, 1), med(2, 1)}, none;
  c.push_back({"base", "dp (no filter)", {}, none});
  c.push_back({"base", "chain F1+F2+F3", {}, chain()});
  // Longer vertical medians: alone, in F1's place (then F2+F3), after the chain.
  for (int r : {3, 4, 5, 6}) {
    const std::string n = fmt::format("vmed{}", 2 * r + 1);
    c.push_back({"vmed", n, {}, {med(r, 0)}});
    c.push_back({"vmed", n + "+F2+F3", {}, std::vector<Filter>{med(r, 0)} + f23});
    c.push_back({"vmed", "chain+" + n, {}, chain() + std::vector<Filter>{med(r, 0)}});
  }
  // Long vertical median only where the centre row's run is uniform, else F1; then F2+F3.
  for (int r : {3, 4, 5, 6})
    for (int l : {8, 16, 32, 64})
      c.push_back(
          {"vmedrun", fmt::format("vmedrun{} L{}+F2+F3", 2 * r + 1, l), {}, {vmed_run(r, l), med(1, 1), med(2, 1)}});
  // Intensity-guided vertical median in F1's place.
  for (int r : {2, 3, 4, 5, 6})
    for (int tau : {4, 8, 16, 32})
      c.push_back(
          {"gvmed", fmt::format("gvmed{} t{}+F2+F3", 2 * r + 1, tau), {}, std::vector<Filter>{gvmed(r, tau)} + f23});
  // Vertical consistency: before the chain and after it.
  for (int k : {3, 4, 5, 6, 8})
    for (int l : {1, 4, 16})
      for (int tau : {-1, 16}) {
        const std::string n = fmt::format("vcons K{} L{}{}", k, l, tau_name(tau));
        c.push_back({"vcons", n + "+chain", {}, std::vector<Filter>{vcons(k, l, tau)} + chain()});
        c.push_back({"vcons", "chain+" + n, {}, chain() + std::vector<Filter>{vcons(k, l, tau)}});
      }
  // Recursive band filter: before / after the chain, alone, with F1 only, between F1 and F2.
  for (int k : {3, 4, 5, 6, 7, 8, 9, 10, 12, 16})
    for (int l : {1, 2, 4, 16})
      for (int tau : {-1, 16, 32}) {
        const std::string n = fmt::format("rband K{} L{}{}", k, l, tau_name(tau));
        const Filter f = rband(k, l, tau);
        c.push_back({"rband", n + "+chain", {}, std::vector<Filter>{f} + chain()});
        c.push_back({"rband", "chain+" + n, {}, chain() + std::vector<Filter>{f}});
        if (l > 2) continue;
        c.push_back({"rband", n, {}, {f}});
        c.push_back({"rband", n + "+F1", {}, {f, med(2, 0)}});
        c.push_back({"rband", "F1+" + n + "+F2+F3", {}, f1 + std::vector<Filter>{f} + f23});
      }
  // Run-based band filter, then the chain.
  for (int k : {5, 8, 10, 12, 16})
    for (int l : {1, 2, 4, 8})
      for (double f : {0.05, 0.1, 0.25, 0.5}) {
        const std::string n = fmt::format("runband K{} L{} f{}", k, l, f);
        c.push_back({"runband", n + "+chain", {}, std::vector<Filter>{rband(k, l, -1, true, f)} + chain()});
      }
  // Inter-scanline DP term, then the chain (integer lambda on the 6-bit costs).
  for (int back : {1, 2, 3}) {
    for (int lambda : {1, 2, 3, 4, 6, 8})
      for (int t : {1, 2, 4, 8}) {
        if (lambda * t > 64) continue;
        const DpSpec s{lambda, t, 0, back};
        c.push_back({"dp", s.key(), s, none});
        c.push_back({"dp", s.key() + " +chain", s, chain()});
      }
    for (int lambda : {2, 4, 8, 12, 16}) {  // indicator: lambda * [|d - d_prev| > 1]
      const DpSpec s{lambda, 1, 1, back};
      c.push_back({"dp", s.key(), s, none});
      c.push_back({"dp", s.key() + " +chain", s, chain()});
    }
    // Fractional lambda: costs and occ scaled by `scale`.
    for (int scale : {2, 4})
      for (int t : {1, 2, 4, 8})
        for (int dz : {0, 1}) {
          if (dz && t > 4) continue;
          const DpSpec s{1, t, dz, back, scale};
          c.push_back({"dp", s.key(), s, none});
          c.push_back({"dp", s.key() + " +chain", s, chain()});
        }
  }
  // Edge-dependent occlusion penalty: occ `o` in flat areas, `e` where the left image has an
  // intensity step above T (lower: depth edges are intensity edges), with the model's F0 (K 8,
  // 10, 12) and the chain; o == e is the uniform penalty.
  for (int o : {8, 9, 10, 11, 12, 13})
    for (int e : {5, 6, 7, 8})
      for (int thr : {8, 12, 16, 20, 24, 32}) {
        if (e > o || (e == o && thr != 16)) continue;
        const DpSpec s{0, 0, 0, 0, 1, o, e, thr};
        c.push_back({"dpedge", s.key() + " +chain", s, chain()});
        for (int k : {8, 10, 12})
          c.push_back({"dpedge", fmt::format("{} +rband K{} L1+chain", s.key(), k), s,
                       std::vector<Filter>{rband(k, 1, -1)} + chain()});
      }
  // The DP term (fed from two or three rows above) together with a band filter.
  for (int back : {2, 3})
    for (int t : {2, 4, 8}) {
      const DpSpec s{1, t, 0, back, 4};
      for (int k : {8, 12})
        c.push_back({"dp+band", fmt::format("{} +rband K{} L1+chain", s.key(), k), s,
                     std::vector<Filter>{rband(k, 1, -1)} + chain()});
      c.push_back({"dp+band", s.key() + " +runband K12 L2 f0.25+chain", s,
                   std::vector<Filter>{rband(12, 2, -1, true, 0.25)} + chain()});
    }
  return c;
}

struct Score {
  double bad = 0, s1 = 0, s5 = 0, s8 = 0;
};

int run(int argc, char** argv) {
  CLI::App app{"Streak study (issue 21): bad-1.0 and the streak measure of the post chain and of candidates"};
  std::string dataset, json_out, dump_dir;
  std::vector<std::string> groups, detail;
  app.add_option("dataset", dataset, "dataset folder (scene subfolders, ../shared/datasets layout)")->required();
  app.add_option("--json", json_out, "write every candidate's per-scene scores as JSON");
  app.add_option("--groups", groups, "only these candidate groups (base is always run)")->delimiter(',');
  app.add_option("--detail", detail, "print per-scene tables for these candidates (exact names)")->delimiter(',');
  app.add_option("--dump", dump_dir,
                 "write <scene>__<candidate>.png colour maps of the two base and --detail candidates");
  int occ = -1;
  app.add_option("--occ", occ, "DP occlusion penalty register (default: Regs::defaults)")
      ->check(sm::tools::int_in(0, 255));
  if (const auto rc = parse_args(app, argc, argv)) return *rc;
  quiet_opencv();

  std::vector<Candidate> cands;
  for (auto& c : candidates())
    if (c.group == "base" || groups.empty() || std::find(groups.begin(), groups.end(), c.group) != groups.end())
      cands.push_back(std::move(c));
  std::vector<size_t> det_user;  // --detail candidates, checked before the long run
  for (const auto& n : detail) {
    auto it = std::find_if(cands.begin(), cands.end(), [&](const Candidate& c) { return c.name == n; });
    if (it == cands.end()) throw ToolError(fmt::format("--detail: no candidate '{}'", n));
    det_user.push_back(static_cast<size_t>(it - cands.begin()));
  }

  const std::vector<std::string> classic = {"cones", "teddy", "tsukuba", "venus"};
  std::vector<std::string> names;
  std::vector<std::vector<Score>> score(cands.size());  // [candidate][scene]
  for (const std::string& dir : list_scenes(dataset)) {
    if (!is_scene_dir(dir)) continue;
    const Scene s = load_scene(dir);
    HwConfig hw;  // paper defaults: CENSUS 15, SW 5, 128 levels, as sm_evaluate
    hw.max_width = s.left.cols;
    hw.max_height = s.left.rows;
    Regs regs = Regs::defaults(hw);
    if (occ >= 0) regs.occ = static_cast<uint8_t>(occ);
    regs.filter_enable = 7;  // the chain F1..F3 without F0: the study's "chain" candidate is checked against it
    const PipelineResult r = run_pipeline(to_image8(s.left), to_image8(s.right), hw, regs, true);
    // The study's own DP and chain reproduce the model's (same functions, same bits).
    if (dp_vert(r.agg, r.rl, regs.occ, hw, DpSpec{}) != r.dp)
      throw std::logic_error(s.name + ": DP differs from the model");
    const Ctx ctx{hw, r.rl};
    // The model's post_band is the study's rband with L 1 and no intensity test.
    for (int k : {8, 12})
      if (post_band(r.dp, hw, k) != rband(k, 1, -1)(r.dp, ctx))
        throw std::logic_error(s.name + ": post_band differs from the study's band filter");
    std::map<std::string, DispImage> dps{{"dp", r.dp}};
    for (size_t c = 0; c < cands.size(); ++c) {
      const std::string key = cands[c].dp.key();
      if (!dps.count(key)) dps.emplace(key, dp_vert(r.agg, r.rl, regs.occ, hw, cands[c].dp));
      DispImage d = dps.at(key);
      for (const Filter& f : cands[c].post) d = f(d, ctx);
      if (cands[c].name == "chain F1+F2+F3" && d != r.post)
        throw std::logic_error(s.name + ": chain differs from the model");
      const cv::Mat e = disp_to_float(d);
      if (!dump_dir.empty() && (c < 2 || std::find(det_user.begin(), det_user.end(), c) != det_user.end())) {
        std::string file = cands[c].name;
        for (char& ch : file)
          if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
        write_image_atomic(dump_dir + "/" + s.name + "__" + file + ".png", disp_to_colour(e, hw.disp));
      }
      score[c].push_back({bad1(e, s.gt, s.nonocc).bad_pct(), streaks(e, s.gt, s.nonocc, 1).streak_pct(),
                          streaks(e, s.gt, s.nonocc, 5).streak_pct(), streaks(e, s.gt, s.nonocc, 8).streak_pct()});
    }
    names.push_back(s.name);
    fmt::print(stderr, "{} done\n", s.name);
  }
  if (names.empty()) throw ToolError(fmt::format("no scenes in {}", dataset));

  auto mean = [&](size_t c, double Score::*m, bool classic_only) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < names.size(); ++i)
      if (!classic_only || std::find(classic.begin(), classic.end(), names[i]) != classic.end()) {
        sum += score[c][i].*m;
        ++n;
      }
    return n ? sum / n : 0.0;
  };
  const size_t base = 1;  // the chain
  fmt::print("means over {} scenes (classic 4: {}); better = scenes with lower bad-1.0 than the chain\n\n",
             names.size(), fmt::join(classic, ", "));
  fmt::print(
      "| group | candidate | bad-1.0 ({}) | bad-1.0 (classic 4) | streak-1 | streak-5 | streak-8 | streak-5 (classic "
      "4) | "
      "better |\n",
      names.size());
  fmt::print("|---|---|---|---|---|---|---|---|---|\n");
  nlohmann::json js = nlohmann::json::array();
  for (size_t c = 0; c < cands.size(); ++c) {
    int better = 0;
    for (size_t i = 0; i < names.size(); ++i) better += score[c][i].bad < score[base][i].bad;
    fmt::print("| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {} |\n", cands[c].group,
               cands[c].name, mean(c, &Score::bad, false), mean(c, &Score::bad, true), mean(c, &Score::s1, false),
               mean(c, &Score::s5, false), mean(c, &Score::s8, false), mean(c, &Score::s5, true), better);
    nlohmann::json sc;
    for (size_t i = 0; i < names.size(); ++i)
      sc[names[i]] = {{"bad1", score[c][i].bad},
                      {"streak1", score[c][i].s1},
                      {"streak5", score[c][i].s5},
                      {"streak8", score[c][i].s8}};
    js.push_back({{"group", cands[c].group}, {"name", cands[c].name}, {"scenes", sc}});
  }
  // Each family's best setting, chosen on the means over all scenes: the lowest bad-1.0 among
  // the settings that at least halve the chain's streak-5 without raising its bad-1.0; if
  // none does, the lowest streak-5 among those not raising bad-1.0; else the lowest bad-1.0.
  const double bad0 = mean(base, &Score::bad, false), s50 = mean(base, &Score::s5, false);
  std::vector<std::string> fams;
  for (const auto& c : cands)
    if (c.group != "base" && std::find(fams.begin(), fams.end(), c.group) == fams.end()) fams.push_back(c.group);
  std::vector<size_t> det = {0, base};
  fmt::print(
      "\nbest setting per family (rule: halves streak-5, bad-1.0 not higher -> lowest bad-1.0; else bad-1.0 not "
      "higher -> lowest streak-5; else lowest bad-1.0)\n\n");
  fmt::print("| family | best setting | rule | bad-1.0 ({}) | bad-1.0 (classic 4) | streak-1 | streak-5 | streak-8 |\n",
             names.size());
  fmt::print("|---|---|---|---|---|---|---|---|\n");
  for (size_t c : {size_t{0}, base})
    fmt::print("| base | {} | - | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n", cands[c].name,
               mean(c, &Score::bad, false), mean(c, &Score::bad, true), mean(c, &Score::s1, false),
               mean(c, &Score::s5, false), mean(c, &Score::s8, false));
  for (const auto& fam : fams) {
    size_t best = cands.size();
    int rule = 0;
    for (int tier = 1; tier <= 3 && best == cands.size(); ++tier)
      for (size_t c = 0; c < cands.size(); ++c) {
        if (cands[c].group != fam) continue;
        const double b = mean(c, &Score::bad, false), s5 = mean(c, &Score::s5, false);
        const bool ok = tier == 1 ? (s5 <= s50 / 2 && b <= bad0) : tier == 2 ? b <= bad0 : true;
        if (!ok) continue;
        const bool by_streak = tier == 2;
        if (best == cands.size() ||
            (by_streak ? s5 < mean(best, &Score::s5, false) : b < mean(best, &Score::bad, false))) {
          best = c;
          rule = tier;
        }
      }
    det.push_back(best);
    fmt::print("| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n", fam, cands[best].name,
               rule == 1   ? "halved"
               : rule == 2 ? "not halved"
                           : "raises bad-1.0",
               mean(best, &Score::bad, false), mean(best, &Score::bad, true), mean(best, &Score::s1, false),
               mean(best, &Score::s5, false), mean(best, &Score::s8, false));
  }
  det.insert(det.end(), det_user.begin(), det_user.end());
  for (auto [title, m] : {std::pair<const char*, double Score::*>{"bad-1.0 %", &Score::bad},
                          {"streak-1 %", &Score::s1},
                          {"streak-5 %", &Score::s5},
                          {"streak-8 %", &Score::s8}}) {
    fmt::print("\n{} per scene\n\n| scene |", title);
    for (size_t c : det) fmt::print(" {} |", cands[c].name);
    fmt::print("\n|---|{}\n", fmt::join(std::vector<std::string>(det.size(), "---|"), ""));
    for (size_t i = 0; i < names.size(); ++i) {
      fmt::print("| {} |", names[i]);
      for (size_t c : det) fmt::print(" {:.2f} |", score[c][i].*m);
      fmt::print("\n");
    }
    for (bool cl : {false, true}) {
      fmt::print("| mean ({}) |", cl ? "classic 4" : fmt::format("{}", names.size()));
      for (size_t c : det) fmt::print(" {:.2f} |", mean(c, m, cl));
      fmt::print("\n");
    }
  }
  if (!json_out.empty()) write_text_atomic(json_out, js.dump(1));
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return guarded_main("sm_streak_study", run, argc, argv); }
