// Direct test of sm_edge_clamp (the census border clamp along one window line) against
// its definition: for every contiguous inside run [a, b] that holds the centre and
// random comparison bits from a fixed seed, output i = bits[clamp(i, a, b)]. Every
// legal mask is tried, so a wrong one-hot or a select on the wrong side shows.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>

#include SM_VTOP_H
#include "sm_block_test.hpp"

namespace {
constexpr int kN = SM_P_N;
constexpr int kR = (kN - 1) / 2;
}  // namespace

int main(int argc, char** argv) {
  static_assert(kN <= 31, "ports are one word");
  sm::test::BlockTest<SM_VTOP> t{"sm_edge_clamp direct test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(0xc1a3bu);
  for (int a = 0; a <= kR; ++a) {
    for (int b = kR; b < kN; ++b) {
      const uint32_t ok = ((1u << (b + 1)) - 1) & ~((1u << a) - 1);
      for (int round = 0; round < 64; ++round) {
        const uint32_t bits = static_cast<uint32_t>(rng()) & ((1u << kN) - 1);
        t->ok = ok;
        t->bits = bits;
        t->eval();
        uint32_t want = 0;
        for (int i = 0; i < kN; ++i) want |= ((bits >> std::clamp(i, a, b)) & 1u) << i;
        t.check(t->q == want,
                [&] { return fmt::format("inside {}..{} bits {:#x}: q {:#x} want {:#x}", a, b, bits, t->q, want); });
      }
    }
  }
  return t.finish(fmt::format("tb_edge_clamp N={}", kN));
}
