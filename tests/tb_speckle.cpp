// Block test of sm_speckle (the speckle stage, docs/algorithm.md 9.8) against the model's
// SpeckleStage, beat by beat: frames of surfaces with islands of every size, invalid
// pixels and words anywhere, at odd widths; binary combs for the longest finds; frames
// shorter than ROWS (several frames in the held rows), a flat frame whose region's counts
// saturate, back to back or with 0..ROWS + 2 virtual rows between them, after beats of no
// row (the fill after reset); the registers per frame (off, 0, the greatest, ...) and
// garbage on them between frames, as on every idle beat; random ce gaps, and ce held while
// the labeller is SLACK beats behind. Every output beat's sideband and word are checked
// (the first SLACK empty), the real ones' order too, and the run must clear speckles, keep
// trusted regions (few pixels failing left-right) and (small tables) label KEEP pixels, or
// the bench has tested nothing.
#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "beat_schedule.hpp"
#include "sm_block_test.hpp"
#include "speckle.hpp"

using namespace sm;
using namespace sm::test;

namespace {

// A surface of a few slanted planes with steps, islands (1..12 pixels) at levels of their
// own, a tenth invalid and now and then a word anywhere (16 bits of Q.4). Confidence bit 7
// (left-right passed): in a frame with `trusty` set, all but one pixel in 12 on the surface
// and on every other island, so some regions are trusted and some are not, and every
// fourth island is 4 x 4 with one pixel failing (16 x 1 failing = 16 pixels: the rule's
// edge, not trusted); else at random.
OutImage random_frame(std::mt19937& rng, int w, int h, bool trusty) {
  OutImage m(w, h);
  const int step = 8 + static_cast<int>(rng() % 40);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int q = 400 + (x * 3 / std::max(1, w / 3)) * step + y + static_cast<int>(rng() % 7);
      const bool valid = rng() % 10 != 0;
      unsigned byte = rng() & 0xff;
      if (trusty) byte = (byte & 0x7f) | (rng() % 12 != 0 ? 0x80 : 0);
      m.at(x, y) = make_out_word(valid, byte, rng() % 40 == 0 ? rng() & 0xffff : static_cast<unsigned>(q), byte);
    }
  const int islands = w * h / 12;
  for (int i = 0; i < islands; ++i) {
    const bool edge = trusty && i % 4 == 1;
    const int iw = edge ? 4 : 1 + static_cast<int>(rng() % 4), ih = edge ? 4 : 1 + static_cast<int>(rng() % 3);
    const int x0 = static_cast<int>(rng() % static_cast<unsigned>(w)),
              y0 = static_cast<int>(rng() % static_cast<unsigned>(h));
    const unsigned q = 2000 + rng() % 3000, conf = trusty && i % 2 == 0 ? 0xda : 0x5a;
    for (int y = y0; y < std::min(h, y0 + ih); ++y)
      for (int x = x0; x < std::min(w, x0 + iw); ++x)
        m.at(x, y) = make_out_word(true, edge && (x > x0 || y > y0) ? 0xda : conf, q + (rng() & 1));
  }
  return m;
}

// A binary comb: one-pixel teeth on even columns, invalid columns between, joined below
// them by one bridge pixel per pair of groups at row R + l for groups of 2^l teeth. Each
// bridge merges two regions of equal rank, so the finds follow the longest chains union
// by rank allows (log2 of the teeth).
OutImage comb_frame(int w, int h) {
  OutImage m(w, h);
  const int teeth = (w + 1) / 2, tooth_rows = std::max(1, h / 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int l = y - tooth_rows, i = x / 2;
      const bool bridge =
          x % 2 == 1 && l >= 0 && l < 16 && (i + 1) % (1 << l) == 0 && (i + 1) % (2 << l) != 0 && i + 1 < teeth;
      m.at(x, y) = make_out_word(x % 2 == 0 || bridge, 0x33, 640);
    }
  return m;
}

// One flat region of every pixel, all failing left-right: at 320 x 40 its size and its
// count of failing pixels saturate (8,191).
OutImage flat_frame(int w, int h) {
  OutImage m(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at(x, y) = make_out_word(true, 0x11, 640);
  return m;
}

struct Beat {
  uint8_t side = 0;
  uint32_t word = 0;
  int frame = -1;  // the frame whose registers a first beat carries
};

}  // namespace

int main(int argc, char** argv) {
  BlockTest<SM_VTOP> t{"speckle stage block test"};
  std::vector<int> widths = {SM_P_MAX_WIDTH};
  int h = 9, frames = 6, idle = 25, gap = 1;
  t.option("--widths", widths, "active widths, one group of frames each").delimiter(',').range(2, SM_P_MAX_WIDTH);
  t.option("--height", h, "rows of the tallest frames").range(1, 4096);
  t.option("--frames", frames, "frames per width").range(1, 1000);
  t.option("--idle", idle, "percent of clocks the schedule holds ce low").range(0, 95);
  t.option("--gap", gap, "clocks from a ce to the next at least (sm_top's pacing F)").range(1, 64);
  if (auto rc = t.parse(argc, argv)) return *rc;
  constexpr int kRows = SM_P_ROWS;
  std::mt19937 rng(2468);
  auto& tb = t.tb();
  tb->ce = 0;
  tb->s_side = 0;
  t.reset(3);
  t.ce_schedule(97, idle, gap);
  SpeckleStage model(SM_P_MAX_WIDTH, kRows, SM_P_LABELS);
  // (en, size, diff, trust) per frame, in turn
  const SpeckleRegs regs[] = {{1, 20, 8, 2}, {1, 0, 0, 0},     {1, 4095, 255, 100},
                              {0, 6, 8, 0},  {1, 2, 16, 4095}, {1, 40, 3, 5}};
  constexpr long kSlack = SM_P_SLACK;  // output beat k is the model's beat k - SLACK
  long taken = 0, cleared = 0, held = 0;
  std::vector<SpeckleStage::Beat> want;  // the model's output beats, in order
  for (const int w : widths) {
    std::vector<int> heights;
    std::vector<OutImage> in;
    std::vector<Beat> sched;
    auto virtual_rows = [&](int n) {
      for (int r = 0; r < n; ++r)
        for (int x = 0; x < w; ++x)
          sched.push_back({static_cast<uint8_t>(x == 0 ? kSol : 0), static_cast<uint32_t>(rng())});
    };
    // after reset the pipeline's fill: beats of no row (no sol) before the first row starts
    if (taken == 0)
      for (int i = 0; i < 5; ++i) sched.push_back({0, static_cast<uint32_t>(rng())});
    for (int f = 0; f < frames; ++f) {
      // tall frames, a row, two rows, frames shorter than the held rows
      const int fh = f % 3 == 0 ? h : f % 3 == 1 ? 1 + f % 2 : std::max(1, std::min(h, kRows / 2 + 1));
      heights.push_back(fh);
      in.push_back(f % 7 == 6   ? flat_frame(w, fh)
                   : f % 4 == 3 ? comb_frame(w, fh)
                                : random_frame(rng, w, fh, f % 2 == 0 || f % 6 == 5));
      for (int y = 0; y < fh; ++y)
        for (int x = 0; x < w; ++x)
          sched.push_back({static_cast<uint8_t>(kReal | (x == 0 ? kSol : 0) | (x + y == 0 ? kSof : 0) | (f & 3) << 3),
                           in.back().at(x, y), x + y == 0 ? f : -1});
      // before the flat frame every held pixel is decided, so its region gets a label
      if ((f + 1) % 7 == 6)
        virtual_rows(kRows + 2);
      else
        virtual_rows(rng() % 3 == 0 ? 0 : static_cast<int>(rng() % (kRows + 3)));
    }
    // the last frame out (and the held rows of width w before the next width)
    virtual_rows(kRows + 1 + static_cast<int>((kSlack + w - 1) / w));
    t.expect_frames(w, heights);
    int cur = 0;
    for (size_t k = 0; k < sched.size();) {
      const bool wanted = t.next_ce();
      const bool c = wanted && tb->ready;
      held += wanted && !c;
      tb->ce = c;
      const Beat& b = sched[k];
      if (b.frame >= 0) cur = b.frame;
      const SpeckleRegs& r = regs[cur % 6];
      if (c) {
        tb->s_side = b.side;
        tb->s_word = b.word;
      } else {  // the stage holds: nothing here may reach it
        tb->s_side = rng() & 31;
        tb->s_word = static_cast<uint32_t>(rng());
      }
      // the registers matter only with a first beat; garbage otherwise
      const bool first = c && b.frame >= 0;
      tb->en = first ? r.en : rng() & 1;
      tb->size = first ? r.size : rng() & 0xfff;
      tb->diff = first ? r.diff : rng() & 0xff;
      tb->trust = first ? r.trust : rng() & 0xfff;
      const SpeckleRegs seen{static_cast<uint8_t>(tb->en), static_cast<uint16_t>(tb->size),
                             static_cast<uint8_t>(tb->diff), static_cast<uint16_t>(tb->trust)};
      tb.tick();
      if (!c) continue;
      ++k;
      want.push_back(model.step(b.side, b.word, seen));
      if (taken < kSlack) {  // the prefill
        t.check(tb->m_side == 0, [&] { return fmt::format("prefill beat {}: side {:#x}", taken, tb->m_side); });
      } else {
        const SpeckleStage::Beat& e = want[static_cast<size_t>(taken - kSlack)];
        t.check(tb->m_side == e.side && tb->m_word == e.word, [&] {
          return fmt::format("w {} beat {}: side {:#x} word {:#010x}, model side {:#x} word {:#010x}", w, taken,
                             tb->m_side, tb->m_word, e.side, e.word);
        });
        if (tb->m_side & kReal) {
          if (!t.next_out(tb->m_side)) break;
          cleared += tb->m_word == kOutSpeckle;
        }
      }
      ++taken;
    }
    t.all_out(fmt::format("w {}: ", w));
  }
  const SpeckleStats& st = model.stats();
  t.check(cleared > 0, "no speckle was cleared: the stimulus tests nothing");
  // (two labels: nearly every region is KEEP, so none is judged)
  if (SM_P_LABELS > 2) t.check(st.trusted > 0, "no region was trusted: SPECKLE_TRUST untested");
  if (SM_P_LABELS < 64) t.check(st.keep_pixels > 0, "the table never filled: KEEP untested");
  return t.finish(
      fmt::format("tb_speckle MAX_WIDTH={} ROWS={} LABELS={} SLACK={} widths {}", SM_P_MAX_WIDTH, kRows, SM_P_LABELS,
                  kSlack, widths.size()),
      fmt::format(" ({} beats, {} cleared, {} trusted, {} KEEP, peak {} labels, longest find {}, ce held {} "
                  "times)",
                  taken, cleared, st.trusted, st.keep_pixels, st.peak_labels, st.longest_find, held));
}
