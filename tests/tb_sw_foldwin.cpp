// Direct test of sm_sw_foldwin (the folded aggregation's column window) against its
// definition: on a step of group g, win[k] is group g of the column that entered k + 1
// beats before the one written now. Columns are random from a fixed seed, steps come
// with idle clocks between them (en low), and a second run after a reset mid-beat
// checks that the counters restart. Banks narrower than a group (BANK_W < W) and the
// unused N = 1 are among the ctest points, so a bank that writes or reads the wrong bits
// or slot shows.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "beat_schedule.hpp"
#include "sm_block_test.hpp"
#include "sm_port.hpp"

namespace {
constexpr int kW = SM_P_W;
constexpr int kN = SM_P_N;
constexpr int kF = SM_P_F;

using Group = std::vector<uint32_t>;  // W bits in 32-bit words
using Column = std::vector<Group>;    // F groups

Group random_group(std::mt19937& rng) {
  Group g(static_cast<size_t>((kW + 31) / 32));
  for (auto& w : g) w = static_cast<uint32_t>(rng());
  if (kW % 32) g.back() &= (uint32_t{1} << (kW % 32)) - 1;
  return g;
}

// Bits [k*W, (k+1)*W) of the win port as 32-bit words.
template <class T>
Group win_group(const T& win, int k) {
  Group g(static_cast<size_t>((kW + 31) / 32));
  for (int b = 0; b < kW; b += 32)
    g[static_cast<size_t>(b / 32)] = sm::test::port_bits(win, k * kW + b, std::min(32, kW - b));
  return g;
}
}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_sw_foldwin direct test"};
  int beats = 40;
  int idle = 30;
  uint32_t seed = 7;
  t.option("--beats", beats, "beats of each run").range(1, 100000);
  t.option("--idle", idle, "percent of clocks with en low").range(0, 95);
  t.option("--seed", seed, "random seed");
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(seed);
  sm::test::CeGen steps_at(seed, idle);  // the clocks that make a step, as other benches' ce

  // Run 0 ends mid-beat; the reset before run 1 must restart the counters at slot 0,
  // group 0, whatever the RAM still holds.
  for (int run = 0; run < 2; ++run) {
    t->en = 0;
    t.reset(3);
    const int steps = beats * kF - (run == 0 ? kF / 2 : 0);
    std::deque<Column> hist;  // hist[0]: the column being written, then older ones
    for (int s = 0; s < steps; ++s) {
      while (!steps_at.next()) {
        t->en = 0;
        t.tick();
      }
      const int g = s % kF;
      if (g == 0) {
        hist.emplace_front(static_cast<size_t>(kF));
        if (hist.size() > static_cast<size_t>(kN) + 1) hist.pop_back();
      }
      hist.front()[static_cast<size_t>(g)] = random_group(rng);
      t->en = 1;
      sm::test::set_port_words(t->col, hist.front()[static_cast<size_t>(g)], kW);
      t->eval();
      for (int k = 0; k < kN && static_cast<size_t>(k) + 1 < hist.size(); ++k) {
        const Group want = hist[static_cast<size_t>(k) + 1][static_cast<size_t>(g)];
        const Group got = win_group(t->win, k);
        t.check(got == want, [&] {
          return fmt::format("run {} step {} (beat {}, group {}): win[{}] {:#x} want {:#x}", run, s, s / kF, g, k,
                             fmt::join(got, "_"), fmt::join(want, "_"));
        });
      }
      t.tick();
    }
  }
  return t.finish(fmt::format("tb_sw_foldwin W={} N={} F={} BANK_W={}", kW, kN, kF, SM_P_BANK_W));
}
