// Unit tests of the floating-point reference (tools/float_ref, issue 21): a known answer on
// a constant-disparity random-texture pair, and the link to the bit-exact model with every
// simplification on.
//
// What "equal" means here: with all simplifications on, every quantity the float
// reference computes is an integer (Hamming costs, shifted costs, integer weights, their
// sums below 2^24, the model's RECIP normalisation in 64-bit integers, an integer
// penalty, DP path sums below 2^53 in double), so float/double hold it exactly and the
// comparisons and ties of the DP are the model's: the disparities must be bit-identical,
// and are checked with ==, not with a tolerance. With any simplification off no equality
// with the model is claimed.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>

#include "aggregate.hpp"
#include "census.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_scenegen.hpp"
#include "dp.hpp"
#include "float_ref/float_ref.hpp"
#include "output_regs.hpp"
#include "pipeline.hpp"
#include "sm_test_util.hpp"

namespace {

// Random texture, right(x) = left(x + d): left pixel x matches right pixel x - d.
void constant_pair(int w, int h, int d, uint32_t seed, sm::Image8& l, sm::Image8& r) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 255);
  l = sm::Image8(w, h);
  r = sm::Image8(w, h);
  for (auto& p : l.px) p = static_cast<uint8_t>(u(rng));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) r.at(x, y) = x + d < w ? l.at(x + d, y) : static_cast<uint8_t>(u(rng));
}

}  // namespace

TEST_CASE("float reference recovers a constant disparity exactly in the interior", "[unit][float_ref]") {
  const int w = 80, h = 32, d = 5;
  sm::Image8 l, r;
  constant_pair(w, h, d, 7, l, r);
  sm::fref::Params p = sm::fref::Params::defaults();
  p.levels = 16;
  p.post = sm::fref::Post::none;
  // The float pipeline, then each simplification alone, then all of them.
  std::vector<std::string> sets = {"none", "all"};
  for (const auto& n : sm::fref::simplify_names()) sets.push_back(n);
  for (const auto& set : sets) {
    p.simp = sm::fref::parse_simplify(set);
    const sm::DispImage out = sm::fref::run(l, r, p, 30);
    // Interior: every row; the columns whose census and aggregation windows (radius 7 +
    // 2) see true matches only, in both views (the right image's last d columns are fresh
    // noise; left columns below d have no match), with a margin of d.
    int wrong = 0;
    for (int y = 0; y < h; ++y)
      for (int x = d + 9; x < w - d - 9; ++x)
        wrong += !(sm::disp_valid(out.at(x, y)) && sm::disp_value(out.at(x, y)) == d);
    INFO("simplify " << set);
    CHECK(wrong == 0);
  }
}

TEST_CASE("float trellis of one line: known matching and ties as the model", "[unit][float_ref]") {
  // A(x, d): 0 at d = 2 for every x, 10 elsewhere; x < 2 can only match d <= x.
  const int n = 12, nd = 4;
  std::vector<float> a(static_cast<size_t>(n) * nd, 10.0f);
  for (int x = 0; x < n; ++x) a[static_cast<size_t>(x) * nd + 2] = 0.0f;
  const auto m = sm::fref::trellis_line(a.data(), n, nd, 4.0);
  for (int x = 2; x < n; ++x) CHECK(m[static_cast<size_t>(x)] == 2);
  // The same integer costs through the model's trellis_dp at every penalty: same output.
  sm::HwConfig hw;
  hw.max_width = 16;
  hw.disp = nd;
  sm::CostVolume cv(n, 1, nd);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> u(0, 20);
  for (size_t i = 0; i < cv.v.size(); ++i) {
    cv.v[i] = static_cast<uint8_t>(u(rng));
    a[i] = cv.v[i];
  }
  sm::fref::CostVol fv;
  fv.w = n;
  fv.h = 1;
  fv.d = nd;
  fv.a = a;
  sm::fref::Params p = sm::fref::Params::defaults();
  p.levels = nd;
  p.simp = sm::fref::Simplify::all();
  for (int occ = 0; occ <= 24; ++occ) {
    INFO("occ " << occ);
    CHECK(sm::fref::trellis(fv, occ, p) == sm::trellis_dp(cv, static_cast<uint8_t>(occ), hw));
  }
}

TEST_CASE("float reference with every simplification on equals the bit-exact model", "[unit][float_ref]") {
  sm::tools::SceneParams sp = sm::test::scene_params(96, 64, 32, 5, 3);
  sp.noise = 2;
  const auto sc = sm::tools::render_scene(sp);
  const sm::Image8 l = sm::tools::to_image8(sc.left), r = sm::tools::to_image8(sc.right);
  sm::HwConfig hw;
  hw.disp = sp.levels;
  hw.max_width = sp.width;
  hw.max_height = sp.height;
  sm::fref::Params p = sm::fref::Params::defaults();
  p.levels = sp.levels;
  p.simp = sm::fref::Simplify::all();

  // Aggregated costs: the same integers as the model's stage functions.
  const sm::Regs regs0 = sm::Regs::defaults(hw);
  const sm::CostVolume agg = sm::sw_aggregate(
      sm::matching_cost(sm::census_transform(l, hw), sm::census_transform(r, hw), l, r, hw), l, regs0.sw_table, hw);
  const sm::fref::CostVol fa = sm::fref::aggregate(l, r, p);
  REQUIRE(fa.a.size() == agg.v.size());
  size_t differ = 0;
  for (size_t i = 0; i < agg.v.size(); ++i) differ += fa.a[i] != static_cast<float>(agg.v[i]);
  CHECK(differ == 0);
  CHECK(fa.unit == 4.0);

  // Whole pipeline (post chain on) at several penalties: raw-scale penalty 4 * occ, the same
  // at edges (OCC_EDGE = OCC: the edge-dependent penalty is the design's, not the paper's).
  for (int occ : {3, 6, 12, 20}) {
    sm::Regs regs = regs0;
    regs.width = sp.width;
    regs.height = sp.height;
    regs.occ = static_cast<uint8_t>(occ);
    regs.occ_edge = regs.occ;                                     // the float reference has the paper's one penalty
    sm::set_output_regs(regs, sm::dense_mode(sm::OutputRegs{}));  // every pixel valid, the Q.4 fraction
    const auto model = sm::run_pipeline(l, r, hw, regs, false);
    INFO("occ " << occ);
    CHECK(sm::fref::run(l, r, p, 4.0 * occ) == model.post);
    // The sub-pixel output: the model's dense output word by word.
    const sm::DispImage dp = sm::fref::trellis(fa, 4.0 * occ, p);
    const std::vector<float> sub =
        sm::fref::smooth(sm::fref::subpix(fa, dp, sm::fref::post(dp, p), p), sp.width, sp.height, p);
    const cv::Mat want = sm::tools::out_to_float(model.out);
    size_t off = 0, fractions = 0;
    for (int y = 0; y < sp.height; ++y)
      for (int x = 0; x < sp.width; ++x) {
        const float v = sub[static_cast<size_t>(y) * sp.width + x];
        off += v != want.at<float>(y, x);
        fractions += v != std::floor(v);
      }
    CHECK(off == 0);
    CHECK(fractions > 0);
  }
}

TEST_CASE("float sub-pixel fit: known answers, real-valued and Q.4", "[unit][float_ref]") {
  // One pixel, 5 levels, the DP's level 2: costs 10 - 2 (k - 2.25)^2 sampled at k = 1, 2, 3
  // have their minimum at 2.25 (a parabola through them is exact).
  sm::fref::CostVol a;
  a.w = a.h = 1;
  a.d = 5;
  auto c = [](double k) { return static_cast<float>(2 * (k - 2.25) * (k - 2.25) + 10); };
  a.a = {c(0), c(1), c(2), c(3), c(4)};
  const sm::DispImage dp(1, 1, sm::make_disp(2, true));
  sm::fref::Params p = sm::fref::Params::defaults();
  p.levels = 5;
  CHECK(sm::fref::subpix(a, dp, dp, p)[0] == Approx(2.25));
  p.simp.frac_q4 = true;
  CHECK(sm::fref::subpix(a, dp, dp, p)[0] == 2.25f);  // 4/16 exactly
  // The filters changed the level: no fraction. Level 0 or levels - 1: no fit.
  const sm::DispImage moved(1, 1, sm::make_disp(3, true));
  CHECK(sm::fref::subpix(a, dp, moved, p)[0] == 3.0f);
  a.a = {c(2), c(3), c(4), c(5), c(6)};  // least cost at level 0
  const sm::DispImage edge(1, 1, sm::make_disp(0, true));
  CHECK(sm::fref::subpix(a, edge, edge, p)[0] == 0.0f);
}

TEST_CASE("float reference switches", "[unit][float_ref]") {
  CHECK(sm::fref::simplify_string(sm::fref::parse_simplify("none")) == "none");
  CHECK(sm::fref::simplify_string(sm::fref::parse_simplify("shift,round")) == "shift,round");
  const auto all = sm::fref::parse_simplify("all");
  CHECK(all.cost_shift);
  CHECK(all.int_penalty);
  CHECK(all.integer_weights());
  CHECK_THROWS_AS(sm::fref::parse_simplify("shift,bogus"), std::invalid_argument);
  CHECK_THROWS_AS(sm::fref::parse_post("median"), std::invalid_argument);
  // exp(-8k/10) * 4 = 4, 1.80, 0.81, 0.36: weights 4, 2, 1, 0.
  const auto t = sm::fref::fitted_table(10);
  CHECK(t[0] == 3);
  CHECK(t[1] == 2);
  CHECK(t[2] == 1);
  CHECK(t[3] == 0);
  // Penalty: raw / 2^shift, an integer with int-penalty.
  sm::fref::Params p = sm::fref::Params::defaults();
  sm::fref::CostVol v;
  v.unit = 4;
  p.simp = sm::fref::parse_simplify("shift");
  CHECK(sm::fref::dp_penalty(30, v, p) == 7.5);
  p.simp = sm::fref::parse_simplify("shift,int-penalty");
  CHECK(sm::fref::dp_penalty(30, v, p) == 8.0);
  CHECK(sm::fref::dp_penalty(5000, v, p) == 255.0);
}
