// Direct test of sm_edge_clamp (the census border clamp along one window line) against
// its definition: for every contiguous inside run [a, b] that holds the centre and
// random comparison bits from a fixed seed, output i = bits[clamp(i, a, b)]. Every
// legal mask is tried, so a wrong one-hot or a select on the wrong side shows.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>

#include SM_VTOP_H
#include <verilated.h>

#include "sm_coverage.hpp"

namespace {
constexpr int kN = SM_P_N;
constexpr int kR = (kN - 1) / 2;
}  // namespace

int main() {
  static_assert(kN <= 31, "ports are one word");
  auto ctx = std::make_unique<VerilatedContext>();
  auto top = std::make_unique<SM_VTOP>(ctx.get());
  sm::CoverageOnExit cov{ctx.get()};
  std::mt19937 rng(0xc1a3bu);
  long passed = 0, failed = 0;
  for (int a = 0; a <= kR; ++a) {
    for (int b = kR; b < kN; ++b) {
      const uint32_t ok = ((1u << (b + 1)) - 1) & ~((1u << a) - 1);
      for (int round = 0; round < 64; ++round) {
        const uint32_t bits = static_cast<uint32_t>(rng()) & ((1u << kN) - 1);
        top->ok = ok;
        top->bits = bits;
        top->eval();
        uint32_t want = 0;
        for (int i = 0; i < kN; ++i) want |= ((bits >> std::clamp(i, a, b)) & 1u) << i;
        if (top->q == want) {
          ++passed;
        } else {
          if (failed == 0)
            fmt::print("FIRST MISMATCH inside {}..{} bits {:#x}: q {:#x} want {:#x}\n", a, b, bits, top->q, want);
          ++failed;
        }
      }
    }
  }
  top->final();
  fmt::print("tb_edge_clamp N={}: {} passed, {} failed\n", kN, passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
