// Block test of the band filter sm_post_band (F0, docs/algorithm.md section 7) against the
// model's post_band: for each width of the list, frames of random, band-structured and
// narrow-range disparity maps of different heights (some of at most K rows, so the
// look-ahead leaves the frame), back to back, then virtual rows; random ce gaps with
// garbage on idle and virtual beats; the enable switched per frame; widths change after a
// flush without a reset, so stale memory contents are in the way. Every real output pixel
// is compared with the model, and its latency (K*W + 1 beats) is checked.
#include <fmt/format.h>

#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "disp_stream.hpp"
#include "sm_block_test.hpp"

using namespace sm;
using namespace sm::test;

namespace {
constexpr int kK = SM_P_K;

// Invalid pixels carry random disparity bits (and valid ones random bits between the
// valid bit and the disparity), so the normalisation and the bypass (which keeps only the
// valid bit and the disparity) are exercised.
DispPix word(std::mt19937& rng, unsigned d, bool valid, unsigned dmask) {
  const unsigned junk = (rng() % 4 == 0) ? (rng() & 0x7fff & ~dmask) : 0;
  return valid ? make_disp((d & dmask) | junk, true) : make_disp(rng() & 0x7fff, false);
}

DispImage random_map(std::mt19937& rng, int w, int h, int dlo, int dhi, int invalid_pct, unsigned dmask) {
  DispImage m(w, h);
  for (auto& p : m.px) {
    const bool valid = static_cast<int>(rng() % 100) >= invalid_pct;
    p = word(rng, dlo + rng() % (dhi - dlo + 1), valid, dmask);
  }
  return m;
}

// Column-constant background (with +-1 jitter) crossed by horizontal bands of 1..K+2 rows
// of another disparity, some returning within 1 of the background, some not.
DispImage band_map(std::mt19937& rng, int w, int h, int disp, unsigned dmask) {
  DispImage m(w, h);
  std::vector<int> base(w);
  for (int x = 0; x < w; ++x) base[x] = 2 + static_cast<int>(rng() % (disp - 4));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int jit = static_cast<int>(rng() % 3) - 1;
      m.at(x, y) = word(rng, static_cast<unsigned>(base[x] + (rng() % 4 == 0 ? jit : 0)), rng() % 25 != 0, dmask);
    }
  for (int s = 0; s < 2 + w * h / 40; ++s) {
    const int y0 = rng() % h, rows = 1 + rng() % (kK + 2), x0 = rng() % w, len = 1 + rng() % 12;
    const unsigned d = rng() % disp;
    for (int y = y0; y < std::min(h, y0 + rows); ++y)
      for (int x = x0; x < std::min(w, x0 + len); ++x) m.at(x, y) = word(rng, d, rng() % 20 != 0, dmask);
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  const HwConfig hw = verilated_config();
  BlockTest<SM_VTOP> t{"sm_post_band block test"};
  std::vector<int> widths{37};
  int h = 12;
  t.option("--widths", widths, "active widths, one frame group each, no reset between")
      .delimiter(',')
      .range(2, hw.max_width);
  t.option("--height", h, "rows of the first frame of each group").range(1, 4096);
  if (auto rc = t.parse(argc, argv)) return *rc;
  unsigned dmask = 1;
  while (dmask + 1 < static_cast<unsigned>(hw.disp)) dmask = dmask * 2 + 1;  // 2^clog2(DISP) - 1
  std::mt19937 rng(4321 + kK);

  auto& tb = t.tb();
  tb->ce = 1;
  tb->width = widths.empty() ? 2 : widths[0];
  tb->s_side = 0;
  t.reset(3);

  t.ce_schedule(99 + kK, 30);
  long replaced = 0;
  for (const int w : widths) {
    tb->width = w;
    // heights: the base, at most K (look-ahead past the bottom), 1 and 2 rows, K + 1
    const std::vector<int> heights = {h, kK, 1, h + 3, kK + 1, 2, std::max(1, kK - 1), h};
    const std::vector<bool> enable = {true, true, true, false, true, true, true, true};
    std::vector<DispImage> in, want;
    for (size_t f = 0; f < heights.size(); ++f) {
      DispImage m;
      switch (f % 3) {
        case 0:
          m = band_map(rng, w, heights[f], hw.disp, dmask);
          break;
        case 1:
          m = random_map(rng, w, heights[f], 3, 6, 15, dmask);
          break;  // many +-1 returns
        default:
          m = random_map(rng, w, heights[f], 0, hw.disp - 1, 10, dmask);
          break;
      }
      const DispImage band = post_band(m, hw, kK);
      for (size_t i = 0; i < m.px.size(); ++i)
        if (disp_valid(m.px[i]) && band.px[i] != (m.px[i] & (kDispValid | dmask))) ++replaced;
      in.push_back(m);
      want.push_back(enable[f] ? band : post_bypass(m, hw));
    }
    const auto sched = make_schedule(w, heights, kK + 2);
    // documented latency (docs/algorithm.md section 7): K*W + 1 beats
    const long latency = static_cast<long>(kK) * w + 1;
    const auto beat_of = beat_index(sched, w, heights);

    t.expect_frames(w, heights);
    // The enable is latched with a frame's first centre at the output stage, K rows after
    // its sof entered (past the ends of short frames), so it shows the setting of the next
    // frame to leave, as sm_frame_sel (NEXT = 1) does in sm_top.
    size_t next_out = 0;
    size_t k = 0;
    const std::string where = fmt::format("width {}: ", w);
    while (k < sched.size()) {
      const bool c = t.next_ce();
      drive_disp(tb.top(), c ? &sched[k++] : nullptr, in, next_out < enable.size() && enable[next_out], rng);
      tb.tick();
      if (!c || !(tb->m_side & kReal)) continue;
      const auto o = t.next_out(tb->m_side, where);
      if (!o) break;
      if (tb->m_side & kSof) next_out = static_cast<size_t>(o->frame) + 1;
      const uint16_t e = want[o->frame].at(o->x, o->y);
      const size_t pix = static_cast<size_t>(o->y) * w + o->x;
      const long lat = static_cast<long>(k - 1) - beat_of[o->frame][pix];  // beats since entry
      if (lat != latency)
        t.fail(fmt::format("{}latency at frame {} x {} y {}: {} beats, documented {}", where, o->frame, o->x, o->y, lat,
                           latency));
      else
        t.check(tb->m_disp == e, [&] {
          return fmt::format("{}frame {} x {} y {} expected {:#06x} got {:#06x}", where, o->frame, o->x, o->y, e,
                             tb->m_disp);
        });
    }
    t.all_out(where);
  }
  // the stimulus must exercise the filter: some pixels replaced from above
  if (replaced == 0) t.fail("no pixel replaced by the model: stimulus too weak");
  return t.finish(fmt::format("tb_post_band MAX_WIDTH={} DISP={} K={}", hw.max_width, hw.disp, kK),
                  fmt::format(" ({} pixels replaced by the band filter)", replaced));
}
