// Direct test of sm_ad_term (the matching cost's intensity term) against the model's
// ad_term: every (left, right) pixel pair, the right pixels of the L lanes offset from
// each other so each lane sees all 65,536 pairs, and lane l's term read from its
// bit-plane position.
#include <fmt/format.h>

#include SM_VTOP_H
#include "census.hpp"
#include "sm_block_test.hpp"
#include "sm_port.hpp"

int main(int argc, char** argv) {
  constexpr int kL = SM_P_L;
  sm::test::BlockTest<SM_VTOP> t{"sm_ad_term direct test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  sm::HwConfig hw;
  hw.ad_shift = SM_P_AD_SHIFT;
  hw.ad_max = SM_P_AD_MAX;
  const int tw = sm::clog2(hw.ad_max + 1);  // TW
  for (int a = 0; a < 256; ++a)
    for (int b = 0; b < 256; ++b) {
      t->a = static_cast<uint8_t>(a);
      for (int l = 0; l < kL; ++l)
        for (int i = 0; i < 8; ++i) sm::test::set_port_bit(t->b, 8 * l + i, (((b + 37 * l) & 255) >> i) & 1);
      t->eval();
      for (int l = 0; l < kL; ++l) {
        const int bl = (b + 37 * l) & 255;
        const unsigned got = sm::test::plane_bits(t->t, l, tw, kL), want = sm::ad_term(a, bl, hw.ad_shift, hw.ad_max);
        t.check(got == want, [&] { return fmt::format("a {} b {} lane {}: term {}, want {}", a, bl, l, got, want); });
      }
    }
  return t.finish(fmt::format("tb_ad_term L={} AD_SHIFT={} AD_MAX={}", kL, hw.ad_shift, hw.ad_max));
}
