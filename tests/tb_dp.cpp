// Block test of sm_dp (docs/algorithm.md, section 6): frames of aggregated-cost
// volumes (structured disparity steps, random full-range costs, tie-heavy costs) with
// a random occlusion penalty per frame, streamed with random ce gaps and garbage on
// virtual beats and idle cycles; every real output pixel is compared with trellis_dp.
// Edge-dependent penalty (s_edge, occ_edge): frame 0 has no flags (trellis_dp, as
// before); every later frame flags about a third of its pixels (column 0 never) with an
// occ_edge different from occ and is compared with trellis_line_pen (pen[x] = flag(x) ?
// occ_edge : occ, pen[W] = occ). s_edge carries the flag of the next beat; virtual rows
// get random flags except at column 0 (the flag the end node sees).
// Folded (SM_P_PU < SM_P_DISP, F = DISP/PU clocks per beat): ce at most every F clocks
// (CeGen's minimum gap) and, as sm_top guarantees, the next beat's input held from the
// clock after a ce up to its ce (no garbage on idle clocks), also for the F clocks
// after reset before the first ce.
// Output-stage evidence (m_matched, m_gap, m_fill_bg, docs/algorithm.md section 9): every
// real pixel is also compared with the model's matched / run_gaps / fill_background of
// its line's DpLine::match. The bench counts the cases the read-out treats apart (a run
// at x = 0, a run at the line end, a line with no match, a run between two matches);
// --require-cases fails when one of them was never compared. Kind 3 (--kinds) makes
// them: occ 0 (an occlusion is free, so a match needs cost 0), on even rows random costs
// 1..max (no match at all without flags), on odd rows structured costs (sparse matches,
// long runs at both ends). Kind 4 (jump_row) makes the largest gaps, DISP - 1 .. DISP - 3;
// --min-gap then requires the largest gap compared to reach a bound.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include SM_VTOP_H
#include "dp.hpp"
#include "evidence.hpp"
#include "sm_block_test.hpp"
#include "held_beats.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kDisp = SM_P_DISP;
constexpr int kCw = SM_P_CW;
constexpr int kS = kDisp / 2;
constexpr int kP = 2;
#ifdef SM_P_PU
constexpr int kF = SM_P_DISP / SM_P_PU;  // clocks per beat
#else
constexpr int kF = 1;
#endif

// Pack DISP CW-bit costs, level k at bit k*CW.
std::vector<uint32_t> pack(const uint8_t* c) { return sm::test::pack_values(c, kDisp, kCw); }

sm::HwConfig make_hw() {
  sm::HwConfig hw;
  hw.max_width = kMaxWidth;
  hw.disp = kDisp;
  for (int c = 3; c <= 15; c += 2)
    for (int sh = 0; sh <= 4; ++sh) {
      hw.census = c;
      hw.cost_shift = sh;
      if (hw.cost_bits() == kCw) return hw;
    }
  throw std::runtime_error(fmt::format("no CENSUS/COST_SHIFT gives CW = {}", kCw));
}

// Structured line: piecewise-constant true disparity with steps; cost grows with the
// distance from the true level, plus a little noise; x - d < 0 gets the maximum.
void structured_row(sm::CostVolume& v, int y, std::mt19937& rng) {
  const int cmax = (1 << kCw) - 1;
  int x = 0;
  while (x < v.w) {
    const int len = 3 + static_cast<int>(rng() % 12);
    const int dt = static_cast<int>(rng() % kDisp);
    for (int k = 0; k < len && x < v.w; ++k, ++x)
      for (int d = 0; d < kDisp; ++d) {
        int c = std::min(cmax, std::abs(d - dt) * 2 + static_cast<int>(rng() % 2));
        if (x - d < 0) c = cmax;
        v.at(x, y, d) = static_cast<uint8_t>(c);
      }
  }
}

// The model's evidence of one line into row y of the frame's planes.
struct EvidencePlanes {
  sm::Image8 matched, gap, fill_bg;
  EvidencePlanes(int w, int h) : matched(w, h), gap(w, h), fill_bg(w, h) {}
  void set_line(const sm::DpLine& line, int y) {
    sm::run_gaps(line.match, &gap.at(0, y));
    sm::fill_background(line.match, &fill_bg.at(0, y));
    for (int x = 0; x < gap.w; ++x) matched.at(x, y) = line.match[static_cast<size_t>(x)] >= 0;
  }
};

// How often each case of the read-out was compared.
struct CaseCounts {
  long matched = 0, run_start = 0, run_end = 0, run_inner = 0, no_match = 0;
  int max_gap = 0;  // largest gap of a run between two matches
  // Pixel x of a line whose match vector is m.
  void add(const std::vector<int>& m, int x) {
    const int w = static_cast<int>(m.size());
    if (m[static_cast<size_t>(x)] >= 0) {
      ++matched;
      return;
    }
    const bool left = std::any_of(m.begin(), m.begin() + x, [](int v) { return v >= 0; });
    const bool right = std::any_of(m.begin() + x + 1, m.begin() + w, [](int v) { return v >= 0; });
    if (!left && !right)
      ++no_match;
    else if (!left)
      ++run_start;
    else if (!right)
      ++run_end;
    else
      ++run_inner;
  }
};

// Jump line: level 0 at the first x0 = 1..4 pixels, then DISP - 1 - j (j = 0..2) pixels
// where every level costs the maximum, then true level DISP - 1 - j (structured costs).
// With an occlusion penalty well below the maximum the path left-occludes the middle
// pixels and climbs to the top level: an unmatched run whose gap is DISP - 1 - j.
void jump_row(sm::CostVolume& v, int y, std::mt19937& rng) {
  const int cmax = (1 << kCw) - 1;
  const int x0 = 1 + static_cast<int>(rng() % 4), top = kDisp - 1 - static_cast<int>(rng() % 3);
  for (int x = 0; x < v.w; ++x)
    for (int d = 0; d < kDisp; ++d) {
      const int dt = x < x0 ? 0 : x < x0 + top ? -1 : top;
      int c = dt < 0 ? cmax : std::min(cmax, std::abs(d - dt) * 2);
      if (x - d < 0) c = cmax;
      v.at(x, y, d) = static_cast<uint8_t>(c);
    }
}

// The occlusion penalty of a frame of the given cost kind (see the header).
uint8_t frame_occ(int kind, std::mt19937& rng) {
  const unsigned cmax = (1u << kCw) - 1;
  switch (kind) {
    case 0:
      return static_cast<uint8_t>(rng() % 48);
    case 1:
      return static_cast<uint8_t>(rng() % 256);
    case 2:
      return static_cast<uint8_t>(rng() % 3);
    case 3:
      return 0;  // occlusions free
    default:
      return static_cast<uint8_t>(1 + rng() % (cmax / 4));  // 4: far below the maximum cost
  }
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_dp block test"};
  sm::test::StreamShape shape{kMaxWidth};
  std::string kinds = "012";
  bool require_cases = false;
  int min_gap = 0;
  // The trellis needs a line of DISP/2 + 3 pixels at least.
  t.stream_options(shape, kS + kP + 1, kMaxWidth);
  t.option("--kinds", kinds, "cost kind of frame f: kinds[f % size] (0 structured, 1 random, 2 ties, 3 occ 0, 4 jump)");
  t.flag("--require-cases", require_cases,
         "fail unless runs at x = 0, at the line end, inside and no-match lines were compared");
  t.option("--min-gap", min_gap, "with --require-cases: the largest gap between two matches must reach this");
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int width = shape.width, rows = shape.rows, frames = shape.frames, idle = shape.idle;
  const uint32_t seed = shape.seed;
  if (kinds.empty() || kinds.find_first_not_of("01234") != std::string::npos) {
    fmt::print(stderr, "tb_dp: --kinds '{}' must be digits 0..4\n", kinds);
    return 2;
  }

  const sm::HwConfig hw = make_hw();
  std::mt19937 rng(seed);
  const int cmax = (1 << kCw) - 1;
  std::vector<sm::CostVolume> vol;
  std::vector<uint8_t> occ, occ_edge;
  std::vector<std::vector<uint8_t>> flags;  // per frame, flags[f][y * width + x]
  std::vector<sm::DispImage> want;
  std::vector<EvidencePlanes> want_ev;
  std::vector<std::vector<std::vector<int>>> matches;  // per frame and row: DpLine::match
  sm::DpScratch scratch;
  sm::DpLine line;
  for (int f = 0; f < frames; ++f) {
    sm::CostVolume v(width, rows, kDisp);
    const int kind = kinds[static_cast<size_t>(f) % kinds.size()] - '0';
    for (int y = 0; y < rows; ++y) {
      if (kind == 0 || (kind == 3 && y % 2 == 1)) {
        structured_row(v, y, rng);
      } else if (kind == 4) {
        jump_row(v, y, rng);
      } else if (kind == 3) {  // costs 1..max: never free
        for (int x = 0; x < width; ++x)
          for (int d = 0; d < kDisp; ++d) v.at(x, y, d) = static_cast<uint8_t>(1 + rng() % cmax);
      } else {
        const int top = kind == 1 ? cmax : 1;  // kind 2: costs 0..1, ties everywhere
        for (int x = 0; x < width; ++x)
          for (int d = 0; d < kDisp; ++d) v.at(x, y, d) = static_cast<uint8_t>(rng() % (top + 1));
      }
    }
    const uint8_t o = frame_occ(kind, rng);
    vol.push_back(v);
    occ.push_back(o);
    std::vector<uint8_t> fl(static_cast<size_t>(width) * rows, 0);
    EvidencePlanes ev(width, rows);
    matches.emplace_back();
    if (f == 0) {  // no flags: today's DP (occ_edge is still random, and unused)
      occ_edge.push_back(static_cast<uint8_t>(rng() & 255));
      want.push_back(sm::trellis_dp(v, o, hw));
      for (int y = 0; y < rows; ++y) {  // the same lines again, for their matches
        sm::trellis_line(v.pix(0, y), width, o, hw, scratch, line);
        ev.set_line(line, y);
        matches.back().push_back(line.match);
      }
    } else {
      // occ_edge != occ. Kinds 1 and 2: occ_edge 0..3. Against kind 1's occ (0..255, mostly
      // far above the costs) the path changes level almost only at flagged pixels, and
      // cheaply enough to reach the high levels (a flag one beat or one group off shows
      // there); kind 2 (costs 0..1, occ 0..2) is ties. Kind 0 in the range of its occ.
      const unsigned range = kind == 0 ? 48 : 4;  // kind 3: occ 0, occ_edge 1..3
      uint8_t oe = static_cast<uint8_t>(rng() % range);
      if (oe == o) oe = static_cast<uint8_t>((o + 1) % range);
      occ_edge.push_back(oe);
      sm::DispImage img(width, rows);
      std::vector<uint8_t> pen(static_cast<size_t>(width) + 1);
      for (int y = 0; y < rows; ++y) {
        for (int x = 0; x < width; ++x) {
          const bool e = x > 0 && rng() % 3 == 0;
          fl[static_cast<size_t>(y) * width + x] = e;
          pen[x] = e ? oe : o;
        }
        pen[width] = o;  // column 0 of the next row, flag 0
        sm::trellis_line_pen(v.pix(0, y), width, pen.data(), hw, scratch, line);
        std::copy(line.disp.begin(), line.disp.end(), &img.at(0, y));
        ev.set_line(line, y);
        matches.back().push_back(line.match);
      }
      want.push_back(img);
    }
    flags.push_back(fl);
    want_ev.push_back(ev);
  }

  const std::vector<int> heights(frames, rows);
  const auto sched = sm::test::make_schedule(width, heights, 3);
  t.expect_frames(width, heights);
  t.ce_schedule(seed * 7919u + 1, idle, kF);
  auto& grng = t.ce_rng();
  auto& tb = t.tb();
  std::vector<uint8_t> garbage(kDisp);
  auto random_cost = [&]() {
    for (auto& g : garbage) g = static_cast<uint8_t>(grng() % (cmax + 1));
    return pack(garbage.data());
  };
  tb->ce = 1;
  tb->width = width;
  tb->s_side = 0;
  tb->occ = 0;
  tb->occ_edge = 0;
  tb->s_edge = 0;
  t.reset(4);

  // Edge flag of every beat: the frame's flags; virtual rows random, column 0 always 0.
  std::vector<uint8_t> beat_flag(sched.size());
  for (size_t i = 0; i < sched.size(); ++i) {
    const auto& b = sched[i];
    if (b.frame >= 0)
      beat_flag[i] = flags[b.frame][static_cast<size_t>(b.y) * width + b.x];
    else
      beat_flag[i] = b.x > 0 && grng() % 2 == 0;
  }

  // The input of one beat, fixed when the beat is first driven (held at F > 1).
  struct Drive {
    uint8_t side = 0, occ = 0, occ_edge = 0, edge = 0;
    std::vector<uint32_t> cost;
  };
  auto beat_input = [&](size_t bi) {
    const sm::test::BeatInfo& b = sched[bi];
    Drive d;
    d.side = b.side;
    d.edge = bi + 1 < sched.size() ? beat_flag[bi + 1] : 0;  // s_edge: the next beat's flag
    if (b.frame >= 0) {
      d.cost = pack(vol[b.frame].pix(b.x, b.y));
      // the frame's penalties are only guaranteed where sm_dp latches them
      const bool latch = b.y == 0 && b.x < kS;
      d.occ = latch ? occ[b.frame] : static_cast<uint8_t>(grng() & 255);
      d.occ_edge = latch ? occ_edge[b.frame] : static_cast<uint8_t>(grng() & 255);
    } else {
      d.cost = random_cost();
      d.occ = static_cast<uint8_t>(grng() & 255);
      d.occ_edge = static_cast<uint8_t>(grng() & 255);
    }
    return d;
  };
  auto drive = [&](const Drive& d) {
    tb->s_side = d.side;
    tb->occ = d.occ;
    tb->occ_edge = d.occ_edge;
    tb->s_edge = d.edge;
    sm::test::set_port_words(tb->s_cost, d.cost, kDisp * kCw);
  };
  auto idle_inputs = [&] {
    tb->s_side = grng() & 31;
    tb->occ = grng() & 255;
    tb->occ_edge = grng() & 255;
    tb->s_edge = grng() & 1;
    sm::test::set_port_words(tb->s_cost, random_cost(), kDisp * kCw);
  };
  bool order_error = false;
  CaseCounts cases;
  auto compare = [&](size_t) {
    const uint8_t side = tb->m_side;
    if (!(side & sm::test::kReal) || order_error) return true;
    const auto o = t.next_out(side);
    if (!o) {  // the rest of the stream is driven, not compared
      order_error = true;
      return true;
    }
    const unsigned exp = want[o->frame].at(o->x, o->y);
    const unsigned got = tb->m_disp;
    t.check(exp == got, [&] {
      return fmt::format("frame {} x {} y {} expected 0x{:04x} got 0x{:04x}", o->frame, o->x, o->y, exp, got);
    });
    const EvidencePlanes& ev = want_ev[o->frame];
    const unsigned em = ev.matched.at(o->x, o->y), eg = ev.gap.at(o->x, o->y), ef = ev.fill_bg.at(o->x, o->y);
    const unsigned gm = tb->m_matched, gg = tb->m_gap, gf = tb->m_fill_bg;
    t.check(em == gm && eg == gg && ef == gf, [&] {
      return fmt::format("frame {} x {} y {} matched/gap/fill_bg expected {}/{}/{} got {}/{}/{}", o->frame, o->x, o->y,
                         em, eg, ef, gm, gg, gf);
    });
    const auto& m = matches[o->frame][static_cast<size_t>(o->y)];
    cases.add(m, o->x);
    if (!em && eg < 255) cases.max_gap = std::max(cases.max_gap, static_cast<int>(eg));
    return true;
  };
  sm::test::run_held_beats(
      t, sched.size(), kF, beat_input, drive, idle_inputs, [](size_t) {}, compare);
  t.all_out();
  fmt::print(
      "tb_dp: compared {} matched pixels; unmatched in runs at x = 0 {}, at the line end {}, between "
      "matches {} (largest gap {}), in lines with no match {}\n",
      cases.matched, cases.run_start, cases.run_end, cases.run_inner, cases.max_gap, cases.no_match);
  if (require_cases) {
    t.check(cases.run_start > 0 && cases.run_end > 0 && cases.run_inner > 0 && cases.no_match > 0,
            [] { return std::string("--require-cases: a read-out case was never compared"); });
    t.check(cases.max_gap >= min_gap,
            [&] { return fmt::format("--require-cases: largest gap {} below --min-gap {}", cases.max_gap, min_gap); });
  }
  return t.finish(fmt::format("tb_dp MAX_WIDTH={} DISP={} CW={} F={} width={}", kMaxWidth, kDisp, kCw, kF, width));
}
