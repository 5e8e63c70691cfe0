// Block test of one post-processing filter (SM_FILTER = 1, 2 or 3; docs/algorithm.md
// section 7): frames of random and structured disparity maps, back to back, random ce
// gaps with garbage on idle and virtual beats, the enable switched per frame; every real
// output pixel is compared with the model.
#include <fmt/format.h>

#include <cstdlib>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "beat_schedule.hpp"
#include "post.hpp"
#include "sm_tb.hpp"
#include "sm_coverage.hpp"

using namespace sm;
using namespace sm::test;

namespace {
DispImage random_map(std::mt19937& rng, int w, int h, int dlo, int dhi, int invalid_pct) {
  DispImage m(w, h);
  for (auto& p : m.px) {
    const bool valid = static_cast<int>(rng() % 100) >= invalid_pct;
    const unsigned d = valid ? dlo + rng() % (dhi - dlo + 1) : rng() & 0x7fff;
    p = make_disp(d, valid);
  }
  return m;
}
// Background, two boxes, and one-row streaks of a wrong disparity.
DispImage structured_map(std::mt19937& rng, int w, int h, int disp) {
  DispImage m(w, h, make_disp(2, true));
  for (int y = h / 4; y < h / 2 + 1; ++y)
    for (int x = w / 5; x < w / 2; ++x) m.at(x, y) = make_disp(disp / 2, true);
  for (int y = h / 2; y < h; ++y)
    for (int x = w / 2 + 3; x < w - 2; ++x) m.at(x, y) = make_disp(disp - 1, true);
  for (int s = 0; s < 4; ++s) {
    const int y = rng() % h, x0 = rng() % w, len = 3 + rng() % 12;
    const unsigned d = rng() % disp;
    for (int x = x0; x < std::min(w, x0 + len); ++x) m.at(x, y) = make_disp(d, true);
  }
  m.at(0, 0) = 0;  // an invalid corner
  return m;
}
}  // namespace

int main(int argc, char** argv) {
  HwConfig hw;
  hw.max_width = SM_P_MAX_WIDTH;
  hw.disp = SM_P_DISP;
  const int w = argc > 1 ? std::atoi(argv[1]) : 37;
  const int h = argc > 2 ? std::atoi(argv[2]) : 9;
  std::mt19937 rng(1234 + SM_FILTER);
  const std::vector<int> heights = {h, h + 2, h - 1, h + 1};
  const std::vector<bool> enable = {true, true, false, true};
  std::vector<DispImage> in, want;
  for (size_t f = 0; f < heights.size(); ++f) {
    DispImage m =
        (f % 2 == 0) ? random_map(rng, w, heights[f], 0, hw.disp - 1, 10) : structured_map(rng, w, heights[f], hw.disp);
    if (f == 2) m = random_map(rng, w, heights[f], 3, 6, 20);  // many ties
    DispImage out = m;
    if (enable[f]) {
      if (SM_FILTER == 1) out = post_vmedian(m, hw);
      if (SM_FILTER == 2) out = post_median3(m, hw);
      if (SM_FILTER == 3) out = post_median53(m, hw);
    }
    in.push_back(m);
    want.push_back(out);
  }
  const auto sched = make_schedule(w, heights, 4);
  // documented latency (docs/algorithm.md section 7): RY*W + RX + 2 beats
  const int ry = SM_FILTER == 2 ? 1 : 2, rx = SM_FILTER == 1 ? 0 : 1;
  const long latency = static_cast<long>(ry) * w + rx + 2;
  std::vector<std::vector<long>> beat_of(heights.size());  // frame -> y*w+x -> beat index
  for (size_t i = 0; i < sched.size(); ++i)
    if (sched[i].frame >= 0) {
      auto& v = beat_of[sched[i].frame];
      v.resize(static_cast<size_t>(w) * heights[sched[i].frame]);
      v[static_cast<size_t>(sched[i].y) * w + sched[i].x] = static_cast<long>(i);
    }

  Testbench<SM_VTOP> tb;
  sm::CoverageOnExit cov{tb->contextp()};
  tb->rst_n = 0;
  tb->ce = 1;
  tb->width = w;
  tb->s_side = 0;
  for (int i = 0; i < 3; ++i) tb.tick();
  tb->rst_n = 1;

  CeGen ce(77 + SM_FILTER, 30);
  OutputOrder order(w, heights);
  long passed = 0, failed = 0;
  bool cur_en = true;
  size_t k = 0;
  try {
    while (k < sched.size()) {
      const bool c = ce.next();
      tb->ce = c;
      if (c) {
        const BeatInfo& b = sched[k++];
        tb->s_side = b.side;
        tb->s_disp = b.frame >= 0 ? in[b.frame].at(b.x, b.y) : static_cast<uint16_t>(rng());
        if (b.frame >= 0 && b.x == 0 && b.y == 0) cur_en = enable[b.frame];
        tb->enable = cur_en;
      } else {  // garbage while the pipeline holds
        tb->s_side = rng() & 31;
        tb->s_disp = static_cast<uint16_t>(rng());
        tb->enable = rng() & 1;
      }
      tb.tick();
      if (c && (tb->m_side & kReal)) {
        const BeatInfo o = order.next(tb->m_side);
        const uint16_t e = want[o.frame].at(o.x, o.y);
        const size_t pix = static_cast<size_t>(o.y) * w + o.x;
        const long lat = static_cast<long>(k - 1) - beat_of[o.frame][pix];  // beats since entry
        if (lat != latency) {
          if (failed == 0)
            fmt::print("latency at frame {} x {} y {}: {} beats, documented {}\n", o.frame, o.x, o.y, lat, latency);
          ++failed;
        } else if (tb->m_disp == e) {
          ++passed;
        } else {
          if (failed == 0)
            fmt::print("first mismatch: frame {} x {} y {} expected {:#06x} got {:#06x}\n", o.frame, o.x, o.y, e,
                       tb->m_disp);
          ++failed;
        }
      }
    }
  } catch (const std::exception& ex) {
    fmt::print("protocol error: {}\n", ex.what());
    ++failed;
  }
  if (!order.done()) {
    fmt::print("not every pixel came out\n");
    ++failed;
  }
  fmt::print("{} passed, {} failed\n", passed, failed);
  return failed ? 1 : 0;
}
