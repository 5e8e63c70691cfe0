// Direct test of the shared window controller sm_win_ctrl: for every beat of a
// schedule with frames of different heights (including frames shorter than the
// window), virtual rows between and after frames, an odd width and random ce gaps,
// c_side / c_x / row_ok / col_ok must describe the beat D_ROWS*W + D_COLS beats back.
// The schedule runs after several pipeline fills (beats with sideband 0 before the
// stream's first SOL, as an upstream stage's reset registers send them): a centre in
// the fill or before the first row is no row, so its c_side is 0, never a SOL, whatever
// the fill's length. A stub row there would make streams' row counts depend on the
// stages' latencies (sm_line_store counts rows from reset).
#include <fmt/format.h>

#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "sm_block_test.hpp"

using sm::test::BeatInfo;

namespace {

// the delay of the centre beat and the window's reach up, down, left and right
constexpr int kDRows = SM_P_D_ROWS, kDCols = SM_P_D_COLS;
constexpr int kRUp = SM_P_R_UP, kRDn = SM_P_R_DN, kRL = SM_P_R_L, kRR = SM_P_R_R;

struct Segment {
  int height;        // rows of the frame
  int virtual_rows;  // flush rows after it
};

// Frames back to back or separated by virtual rows, each virtual row carrying the
// ftag of the frame before it (as the input sequencer sends them).
std::vector<BeatInfo> build(int w, const std::vector<Segment>& segs, std::vector<int>* heights) {
  std::vector<BeatInfo> s;
  for (size_t f = 0; f < segs.size(); ++f) {
    heights->push_back(segs[f].height);
    const auto ftag = static_cast<uint8_t>((f & 3) << 3);
    for (int y = 0; y < segs[f].height + segs[f].virtual_rows; ++y) {
      const bool real = y < segs[f].height;
      for (int x = 0; x < w; ++x) {
        BeatInfo b;
        b.frame = real ? static_cast<int>(f) : -1;
        b.x = x;
        b.y = real ? y : 0;
        b.side = ftag;
        if (real) b.side |= sm::test::kReal;
        if (real && x == 0 && y == 0) b.side |= sm::test::kSof;
        if (x == 0) b.side |= sm::test::kSol;
        s.push_back(b);
      }
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_win_ctrl direct test"};
  int w = 37;
  t.option("--width", w, "active width");
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::vector<int> heights;
  // H = 1 and 2 are shorter than the window; 0 virtual rows puts frames back to back.
  const auto sched = build(w, {{6, 0}, {1, 0}, {2, 1}, {9, 0}, {3, 2}, {kDRows + 1, 0}, {5, kDRows + 2}}, &heights);
  auto& tb = t.tb();
  t.ce_schedule(0x5eed1u, 30);
  std::mt19937 rng(7);
  tb->width = w;
  tb->ce = 1;

  const long delay = static_cast<long>(kDRows) * w + kDCols;
  // one check per beat; its first wrong output is the one reported
  auto fail = [&](long n, const std::string& what) { t.fail(fmt::format("at beat {}: {}", n, what)); };
  // fills shorter and longer than the column delay, and longer than a row
  for (const long fill : {0L, 1L, static_cast<long>(kDCols), static_cast<long>(kDCols) + 2, static_cast<long>(w) + 5}) {
    tb->s_side = 0;
    t.reset(3);
    const long total = fill + static_cast<long>(sched.size());
    for (long n = 0; n < total;) {
      const bool ce = t.next_ce();
      // garbage on the sideband while ce is low: it must not move the state
      tb->s_side = !ce ? static_cast<uint8_t>(rng() & 31) : n < fill ? 0 : sched[n - fill].side;
      tb->eval();
      if (ce) {
        const long cn = n - delay - fill;
        bool ok = true;
        if (cn < 0) {
          // pipeline fill after reset: no frame, no row
          if (tb->c_side != 0) {
            fail(n, fmt::format("fill {}: centre before the first row has c_side {}", fill, tb->c_side));
            ok = false;
          }
        } else {
          const BeatInfo& c = sched[cn];
          if (tb->s_x != sched[n - fill].x) {  // cn >= 0: the entering beat is past the fill
            fail(n, fmt::format("fill {}: s_x expected {} got {}", fill, sched[n - fill].x, tb->s_x));
            ok = false;
          }
          if (tb->c_side != c.side || static_cast<int>(tb->c_x) != c.x) {
            fail(n, fmt::format("fill {}: centre beat {} (frame {}, x {}, y {}): c_side/c_x expected {}/{} "
                                "got {}/{}",
                                fill, cn, c.frame, c.x, c.y, c.side, c.x, tb->c_side, tb->c_x));
            ok = false;
          }
          unsigned row_exp = 0, col_exp = 0;
          for (int j = -kRUp; j <= kRDn; ++j) {
            const int y = c.y + j;
            if (c.frame >= 0 && y >= 0 && y < heights[c.frame]) row_exp |= 1u << (kRUp + j);
          }
          for (int i = -kRL; i <= kRR; ++i) {
            const int x = c.x + i;
            if (x >= 0 && x < w) col_exp |= 1u << (kRL + i);
          }
          if (tb->row_ok != row_exp || tb->col_ok != col_exp) {
            fail(n, fmt::format("fill {}: centre (frame {}, x {}, y {}): row_ok/col_ok expected {:#x}/{:#x} "
                                "got {:#x}/{:#x}",
                                fill, c.frame, c.x, c.y, row_exp, col_exp, tb->row_ok, tb->col_ok));
            ok = false;
          }
        }
        if (ok) t.pass();
        ++n;
      }
      tb.tick();
    }
  }
  return t.finish(fmt::format("tb_win_ctrl D_ROWS={} D_COLS={} R={}/{}/{}/{}", kDRows, kDCols, kRUp, kRDn, kRL, kRR));
}
