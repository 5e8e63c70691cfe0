// Block test of sm_wta (docs/algorithm.md section 9.0): every beat's costs are drawn from
// a fixed seed out of tie-heavy patterns (costs 0..3 or 0..1, all levels equal, V shapes
// and ramps whose minimum sits at levels 0, 1, DISP-2, DISP-1 or next to them, two equal
// minima adjacent or apart, uniform costs), streamed with random ce gaps and idle cycles;
// every real output beat is compared with the model (wta_row, wta_band) and must leave
// exactly LATENCY ce's after its ce (the formula of rtl/sm_wta.v's header), and the
// outputs must not change between ces. The run fails when the stimulus missed a case
// (dw at 0, 1, DISP-2, DISP-1; c2 == c1; all levels equal).
// Folded (SM_P_PU < SM_P_DISP, F = DISP/PU clocks per beat): ce at most every F clocks
// and the next beat's input held from the clock after a ce up to its ce, also for the F
// clocks after reset before the first ce (as tests/tb_dp.cpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

#include SM_VTOP_H
#include "evidence.hpp"
#include "sm_block_test.hpp"
#include "held_beats.hpp"
#include "sm_defs.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kDisp = SM_P_DISP;
constexpr int kCw = SM_P_CW;
#ifdef SM_P_PU
constexpr int kPu = SM_P_PU;
#else
constexpr int kPu = SM_P_DISP;
#endif
constexpr int kF = kDisp / kPu;  // clocks per beat
constexpr int kCmax = (1 << kCw) - 1;

// rtl/sm_wta.v's LATENCY: the tree's NS = ceil(clog2(DISP) / 2) register stages at
// PU = DISP; folded, the ring's floor(D / F) + 1 slots (D = ceil(clog2(PU) / 2) + 2) and
// the output registers.
constexpr int kStages = (sm::clog2(kPu) + 1) / 2;
constexpr int kLatency = kF == 1 ? kStages : (kStages + 2) / kF + 2;

// Pack DISP CW-bit costs, level k at bit k*CW.
std::vector<uint32_t> pack(const uint8_t* c) { return sm::test::pack_values(c, kDisp, kCw); }

// A level near the ends half of the time.
int pick_level(std::mt19937& rng) {
  const int ends[6] = {0, 1, kDisp - 2, kDisp - 1, 2, kDisp - 3};
  const unsigned r = rng() % 12;
  return r < 6 ? ends[r] : static_cast<int>(rng() % kDisp);
}

uint8_t clampc(int v) { return static_cast<uint8_t>(std::min(kCmax, std::max(0, v))); }

// One beat's costs a[0..DISP-1] from one of the patterns.
void make_costs(std::mt19937& rng, uint8_t* a) {
  const unsigned kind = rng() % 8;
  const int t = pick_level(rng);
  switch (kind) {
    case 0:  // uniform over the full range
      for (int d = 0; d < kDisp; ++d) a[d] = clampc(static_cast<int>(rng() % (kCmax + 1)));
      break;
    case 1:    // 0..3: ties everywhere
    case 2: {  // 0..1
      const int top = kind == 1 ? 3 : 1;
      for (int d = 0; d < kDisp; ++d) a[d] = clampc(static_cast<int>(rng() % (top + 1)));
      break;
    }
    case 3: {  // every level equal: 0, CMAX or any
      const unsigned r = rng() % 3;
      const int v = r == 0 ? 0 : r == 1 ? kCmax : static_cast<int>(rng() % (kCmax + 1));
      for (int d = 0; d < kDisp; ++d) a[d] = clampc(v);
      break;
    }
    case 4:    // V shape around t, a little noise
    case 5: {  // the same with an equal cost at t - 1 or t + 1 (inside the masked window)
      const int s = 1 + static_cast<int>(rng() % 3), lo = static_cast<int>(rng() % 3);
      for (int d = 0; d < kDisp; ++d) a[d] = clampc(lo + std::abs(d - t) * s + static_cast<int>(rng() % 2));
      a[t] = clampc(lo);
      if (kind == 5) {
        const int n = t + (rng() % 2 ? 1 : -1);
        if (n >= 0 && n < kDisp) a[n] = clampc(lo);
      }
      break;
    }
    case 6: {  // two equal minima, offsets -3..3 or anywhere; the rest above them
      const int lo = static_cast<int>(rng() % (kCmax + 1));
      for (int d = 0; d < kDisp; ++d) a[d] = clampc(lo + 1 + static_cast<int>(rng() % (kCmax + 1)));
      const int off = rng() % 2 ? static_cast<int>(rng() % 7) - 3 : static_cast<int>(rng() % kDisp) - t;
      a[t] = clampc(lo);
      if (t + off >= 0 && t + off < kDisp) a[t + off] = clampc(lo);
      break;
    }
    default: {  // ramp, least at one end, sometimes flat (ties) at the low end
      const int s = static_cast<int>(rng() % 3);
      const bool up = rng() % 2;
      for (int d = 0; d < kDisp; ++d) a[d] = clampc((up ? d : kDisp - 1 - d) * s + static_cast<int>(rng() % 2));
      break;
    }
  }
}

struct Want {
  unsigned dw, c1, c2, cmax;
  std::array<unsigned, 5> band;
};

Want model(const uint8_t* a) {
  uint8_t dw, c1, c2, cmax;
  sm::wta_row(a, 1, kDisp, &dw, &c1, &c2, &cmax);
  Want w{dw, c1, c2, cmax, {}};
  for (int j = 0; j < 5; ++j) w.band[static_cast<size_t>(j)] = sm::wta_band(a, kDisp, dw, j);
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_wta block test"};
  sm::test::StreamShape shape{37};
  t.stream_options(shape, 1, sm::defs::limit("MAX_WIDTH").max);  // sm_wta keeps no line
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int width = shape.width, rows = shape.rows, frames = shape.frames, idle = shape.idle;
  const uint32_t seed = shape.seed;

  const std::vector<int> heights(frames, rows);
  const auto sched = sm::test::make_schedule(width, heights, (kLatency + width) / width + 1);
  std::mt19937 rng(seed);
  std::vector<uint8_t> cost(sched.size() * kDisp);  // every beat's costs, virtual ones too
  for (size_t i = 0; i < sched.size(); ++i) make_costs(rng, &cost[i * kDisp]);

  t.expect_frames(width, heights);
  t.ce_schedule(seed * 7919u + 1, idle, kF);
  auto& grng = t.ce_rng();
  auto& tb = t.tb();
  std::vector<uint8_t> garbage_cost(kDisp);
  auto drive = [&](size_t bi) {
    tb->s_side = sched[bi].side;
    sm::test::set_port_words(tb->s_cost, pack(&cost[bi * kDisp]), kDisp * kCw);
  };
  tb->ce = 1;
  tb->s_side = 0;
  t.reset(4);

  struct Out {
    unsigned side, dw, c1, c2, cmax;
    uint64_t band;
  };
  auto read_out = [&] {
    return Out{tb->m_side, tb->m_dw, tb->m_c1, tb->m_c2, tb->m_cmax, static_cast<uint64_t>(tb->m_band)};
  };
  auto same = [](const Out& a, const Out& b) {
    return a.side == b.side && a.dw == b.dw && a.c1 == b.c1 && a.c2 == b.c2 && a.cmax == b.cmax && a.band == b.band;
  };
  Out last = read_out();
  long at0 = 0, at1 = 0, at_m2 = 0, at_m1 = 0, tie_c2 = 0, flat = 0;
  // The real output beat (frame, x, y) against the model of the costs a it was sampled with.
  auto compare = [&](const sm::test::BeatInfo& o, const uint8_t* a) {
    const Want w = model(a);
    std::array<unsigned, 5> band{};
    for (int j = 0; j < 5; ++j) band[static_cast<size_t>(j)] = sm::test::port_bits(tb->m_band, j * kCw, kCw);
    const bool ok = w.dw == last.dw && w.c1 == last.c1 && w.c2 == last.c2 && w.cmax == last.cmax && w.band == band;
    t.check(ok, [&] {
      return fmt::format(
          "frame {} x {} y {}: expected dw {} c1 {} c2 {} cmax {} band {} got dw {} c1 {} c2 {} cmax {} band {} "
          "(costs {})",
          o.frame, o.x, o.y, w.dw, w.c1, w.c2, w.cmax, fmt::join(w.band, ","), last.dw, last.c1, last.c2, last.cmax,
          fmt::join(band, ","), fmt::join(a, a + kDisp, ","));
    });
    at0 += w.dw == 0;
    at1 += w.dw == 1;
    at_m2 += w.dw == kDisp - 2;
    at_m1 += w.dw == kDisp - 1;
    tie_c2 += w.c2 == w.c1;
    flat += w.cmax == w.c1;
  };
  auto garbage = [&] {
    tb->s_side = grng() & 31;
    for (auto& g : garbage_cost) g = static_cast<uint8_t>(grng() % (kCmax + 1));
    sm::test::set_port_words(tb->s_cost, pack(garbage_cost.data()), kDisp * kCw);
  };
  auto check_held = [&](size_t bi) {
    const Out o = read_out();
    if (!same(o, last)) t.fail(fmt::format("outputs changed without a ce (beat {})", bi));
    last = o;
  };
  bool order_error = false;
  auto on_ce = [&](size_t bi) {  // ce number bi
    last = read_out();
    const auto side = static_cast<uint8_t>(last.side);
    if (!(side & sm::test::kReal) || order_error) return true;
    const auto o = t.next_out(side);
    if (!o) {  // the rest of the stream is driven, not compared
      order_error = true;
      return true;
    }
    // the beat leaving on ce bi is the one the LATENCY-th ce before (counting this one) sampled
    const long src = static_cast<long>(bi) - kLatency + 1;
    const bool lat_ok = src >= 0 && sched[static_cast<size_t>(src)].frame == o->frame &&
                        sched[static_cast<size_t>(src)].x == o->x && sched[static_cast<size_t>(src)].y == o->y;
    t.check(lat_ok, [&] {
      return fmt::format("frame {} x {} y {} left on ce {}, not on the {}th ce from its own", o->frame, o->x, o->y, bi,
                         kLatency);
    });
    if (lat_ok) compare(*o, &cost[static_cast<size_t>(src) * kDisp]);
    return true;
  };
  sm::test::run_held_beats(
      t, sched.size(), kF, [](size_t bi) { return bi; }, drive, garbage, check_held, on_ce);
  t.all_out();
  // The stimulus itself: every corner case must have been compared at least once.
  const std::pair<const char*, long> cases[] = {{"dw = 0", at0},        {"dw = 1", at1},
                                                {"dw = DISP-2", at_m2}, {"dw = DISP-1", at_m1},
                                                {"c2 = c1", tie_c2},    {"all levels equal", flat}};
  for (const auto& [name, n] : cases)
    if (n == 0) t.fail(fmt::format("stimulus: no pixel with {} was compared", name));
  return t.finish(
      fmt::format("tb_wta DISP={} CW={} PU={} F={} LATENCY={} width={}", kDisp, kCw, kPu, kF, kLatency, width),
      fmt::format(" (dw at 0/1/DISP-2/DISP-1: {}/{}/{}/{}, c2 = c1: {}, flat: {})", at0, at1, at_m2, at_m1, tie_c2,
                  flat));
}
