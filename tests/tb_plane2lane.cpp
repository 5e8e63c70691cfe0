// Direct test of sm_plane2lane (the bit-plane to lane-order transpose of sm_cost's
// counts): random planes from a fixed seed, every output bit checked against its
// definition, lane l bit p = planes bit p*L + l. Configurations cover padded planes
// (P not a multiple of 8), padded lanes (L not a multiple of 8) and several plane
// blocks (P > 8).
#include <fmt/format.h>

#include <cstdint>
#include <random>

#include SM_VTOP_H
#include "sm_block_test.hpp"
#include "sm_port.hpp"

int main(int argc, char** argv) {
  constexpr int kP = SM_P_P, kL = SM_P_L;
  sm::test::BlockTest<SM_VTOP> t{"sm_plane2lane direct test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(0x91a7e5u);
  for (int round = 0; round < 200; ++round) {
    // sparse, dense and balanced patterns: a wrong bit shows in all of them
    const unsigned density = round % 3 == 0 ? 8 : round % 3 == 1 ? 248 : 128;
    for (int i = 0; i < kP * kL; ++i) sm::test::set_port_bit(t->planes, i, (rng() & 255) < density);
    t->eval();
    for (int l = 0; l < kL; ++l) {
      for (int p = 0; p < kP; ++p) {
        const bool want = sm::test::port_bits(t->planes, p * kL + l, 1);
        const bool got = sm::test::port_bits(t->lanes, l * kP + p, 1);
        t.check(want == got,
                [&] { return fmt::format("round {} lane {} bit {}: {} want {}", round, l, p, got, want); });
      }
    }
  }
  return t.finish(fmt::format("tb_plane2lane P={} L={} (bits)", kP, kL));
}
