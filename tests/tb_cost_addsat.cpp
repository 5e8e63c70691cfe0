// Direct test of sm_cost_addsat (the matching cost from the Hamming count and the
// intensity term, at the aggregation's scale) against the definition model/census.hpp
// gives matching_cost, shifted as the aggregation shifts it: min(h + (t << COST_SHIFT),
// CB) >> COST_SHIFT, or CB >> COST_SHIFT where ok is low. Every (h, t) pair with h <= CB
// (the counts sm_popcount can give) and ok both ways, in the lanes of one vector, at
// random lane positions from a fixed seed.
#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "sm_block_test.hpp"
#include "sm_port.hpp"

int main(int argc, char** argv) {
  constexpr int kL = SM_P_L, kHw = SM_P_HW, kTw = SM_P_TW, kShift = SM_P_COST_SHIFT, kCb = SM_P_CB;
  sm::test::BlockTest<SM_VTOP> t{"sm_cost_addsat direct test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  struct Case {
    int h, t;
    bool ok;
  };
  const int cw = sm::clog2((kCb >> kShift) + 1);  // the output's planes
  std::vector<Case> cases;
  for (int h = 0; h <= kCb; ++h)
    for (int tv = 0; tv < (1 << kTw); ++tv)
      for (bool ok : {true, false}) cases.push_back({h, tv, ok});
  std::mt19937 rng(0xadd5u);
  std::shuffle(cases.begin(), cases.end(), rng);
  for (size_t i = 0; i < cases.size(); i += kL) {
    for (int l = 0; l < kL; ++l) {
      const Case& c = cases[(i + l) % cases.size()];
      for (int f = 0; f < kHw; ++f) sm::test::set_port_bit(t->h, f * kL + l, (c.h >> f) & 1);
      for (int f = 0; f < kTw; ++f) sm::test::set_port_bit(t->t, f * kL + l, (c.t >> f) & 1);
      sm::test::set_port_bit(t->ok, l, c.ok);
    }
    t->eval();
    for (int l = 0; l < kL; ++l) {
      const Case& c = cases[(i + l) % cases.size()];
      const unsigned want = (c.ok ? std::min(c.h + (c.t << kShift), kCb) : kCb) >> kShift;
      const unsigned got = sm::test::plane_bits(t->cost, l, cw, kL);
      t.check(got == want,
              [&] { return fmt::format("h {} t {} ok {} lane {}: cost {}, want {}", c.h, c.t, c.ok, l, got, want); });
    }
  }
  return t.finish(fmt::format("tb_cost_addsat L={} HW={} TW={} COST_SHIFT={} CB={}", kL, kHw, kTw, kShift, kCb));
}
