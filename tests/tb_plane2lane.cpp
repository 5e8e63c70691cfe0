// Direct test of sm_plane2lane (the bit-plane to lane-order transpose of sm_cost's
// counts): random planes from a fixed seed, every output bit checked against its
// definition, lane l bit p = planes bit p*L + l. Configurations cover padded planes
// (P not a multiple of 8), padded lanes (L not a multiple of 8) and several plane
// blocks (P > 8).
#include <fmt/format.h>

#include <cstdint>
#include <memory>
#include <random>

#include SM_VTOP_H
#include <verilated.h>

#include "sm_port.hpp"
#include "sm_coverage.hpp"

namespace {

constexpr int kP = SM_P_P;
constexpr int kL = SM_P_L;

}  // namespace

int main() {
  auto ctx = std::make_unique<VerilatedContext>();
  auto top = std::make_unique<SM_VTOP>(ctx.get());
  sm::CoverageOnExit cov{ctx.get()};
  std::mt19937 rng(0x91a7e5u);
  long passed = 0, failed = 0;
  for (int round = 0; round < 200; ++round) {
    // sparse, dense and balanced patterns: a wrong bit shows in all of them
    const unsigned density = round % 3 == 0 ? 8 : round % 3 == 1 ? 248 : 128;
    for (int i = 0; i < kP * kL; ++i) sm::test::set_port_bit(top->planes, i, (rng() & 255) < density);
    top->eval();
    for (int l = 0; l < kL; ++l) {
      for (int p = 0; p < kP; ++p) {
        const bool want = sm::test::port_bits(top->planes, p * kL + l, 1);
        const bool got = sm::test::port_bits(top->lanes, l * kP + p, 1);
        if (want == got) {
          ++passed;
        } else {
          if (failed == 0) fmt::print("FIRST MISMATCH round {} lane {} bit {}: {} want {}\n", round, l, p, got, want);
          ++failed;
        }
      }
    }
  }
  top->final();
  fmt::print("tb_plane2lane P={} L={}: {} bits passed, {} failed\n", kP, kL, passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
