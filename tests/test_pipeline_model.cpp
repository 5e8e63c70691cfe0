// Unit tests of the whole model pipeline: run_pipeline, which streams rows through the
// stage kernels (and, with threads > 1, streams bands of rows on several threads), gives
// every stage's output bit for bit as one thread and as the whole-frame stage functions
// composed by run_frame_stages (the functions the RTL block tests compare against).
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "frame_stages.hpp"
#include "pipeline.hpp"

namespace {

// A textured left image and a right image shifted by a disparity d (right pixel x shows
// the texture at x + d) that steps with the
// row and the column in blocks (near block in the middle), plus noise: costs, occlusions and edges
// of every kind, so that a band boundary in the wrong place changes some output.
std::pair<sm::Image8, sm::Image8> scene(int w, int h, int maxd, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 255), n(-3, 3);
  std::vector<int> tex(static_cast<size_t>(w + 2 * maxd) * h);
  for (auto& v : tex) v = u(rng);
  sm::Image8 l(w, h), r(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool near = x > w / 3 && x < 2 * w / 3 && y > h / 4 && y < 3 * h / 4;
      const int d = near ? maxd - 2 : 1 + (x / 13 + y / 9) % (maxd / 2);
      const size_t row = static_cast<size_t>(y) * (w + 2 * maxd);
      l.at(x, y) = static_cast<uint8_t>(tex[row + x + maxd]);
      r.at(x, y) = static_cast<uint8_t>(std::clamp(tex[row + x + maxd + d] + n(rng), 0, 255));  // L(x) ~ R(x - d)
    }
  return {l, r};
}

void check_equal(const sm::PipelineResult& a, const sm::PipelineResult& b) {
  CHECK(a.bl == b.bl);
  CHECK(a.br == b.br);
  CHECK(a.rl == b.rl);
  CHECK(a.rr == b.rr);
  CHECK(a.raw == b.raw);
  CHECK(a.agg == b.agg);
  CHECK(a.dp == b.dp);
  CHECK(a.post_steps == b.post_steps);
  CHECK(a.post == b.post);
  CHECK(a.out == b.out);
  CHECK(a.objects.objects == b.objects.objects);
  CHECK(a.objects.too_many_objects == b.objects.too_many_objects);
  CHECK(a.objects.table_full == b.objects.table_full);
}

struct Point {
  int w, h, disp, census, sw, cost_shift;
};

}  // namespace

TEST_CASE("run_pipeline: any thread count and the stage functions give the same bits", "[pipeline]") {
  // Odd sizes; the paper's windows and two others; a thread count above the row count.
  const Point pt = GENERATE(Point{67, 29, 16, 15, 5, 2}, Point{53, 23, 10, 7, 7, 0}, Point{41, 17, 12, 9, 3, 1});
  sm::HwConfig hw;
  hw.max_width = pt.w;
  hw.max_height = pt.h;
  hw.disp = pt.disp;
  hw.census = pt.census;
  hw.sw = pt.sw;
  hw.cost_shift = pt.cost_shift;
  hw.validate();
  sm::Regs regs = sm::Regs::defaults(hw);
  regs.occ = 9;
  regs.occ_edge = 3;  // edge-dependent penalties on
  regs.edge_t = 24;
  regs.obj_near = static_cast<uint8_t>(pt.disp / 2);
  regs.obj_min_pixels = 4;
  const auto [l, r] = scene(pt.w, pt.h, pt.disp, static_cast<unsigned>(pt.w));
  const sm::PipelineResult one = sm::run_pipeline(l, r, hw, regs, true, 1);
  REQUIRE(one.dp.px.size() == static_cast<size_t>(pt.w) * pt.h);
  // Not a degenerate frame: several disparities and some near object.
  std::vector<int> seen(static_cast<size_t>(pt.disp), 0);
  for (auto p : one.dp.px) seen[static_cast<size_t>(p & 0xff) % seen.size()] = 1;
  INFO("point " << pt.w << "x" << pt.h << " disp " << pt.disp << " first dp " << one.dp.px[0]);
  CHECK(std::count(seen.begin(), seen.end(), 1) >= 3);
  for (int threads : {2, 3, 64}) {
    INFO("threads " << threads);
    check_equal(sm::run_pipeline(l, r, hw, regs, true, threads), one);
    // Without the volumes: the same disparities.
    const sm::PipelineResult lean = sm::run_pipeline(l, r, hw, regs, false, threads);
    CHECK(lean.dp == one.dp);
    CHECK(lean.post == one.post);
  }
  for (int threads : {1, 3}) {
    INFO("run_frame_stages, threads " << threads);
    check_equal(sm::run_frame_stages(l, r, hw, regs, threads), one);
  }
}
