// Direct test of sm_bitheap (the 6:3 compressor heap shared by the Hamming popcounts and
// the support-weight sums): random heaps from a fixed seed at sparse, dense and balanced
// densities, and per lane row_a + row_b (modulo 2^NC) checked against the heap's sum
// computed from its definition, sum over columns c of 2^c times the number of set bits
// in column c. The column heights come on the command line and must match the H0
// parameter the model was built with (the width of the `bits` port is checked).
#include <fmt/format.h>

#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "sm_block_test.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kNc = SM_P_NC;
constexpr int kL = SM_P_L;

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_bitheap direct test"};
  std::vector<int> heights;
  t.option("--heights", heights, "bits in column 0, 1, ... (as H0)").required();
  if (auto rc = t.parse(argc, argv)) return *rc;
  if (static_cast<int>(heights.size()) != kNc) {
    fmt::print(stderr, "tb_bitheap: {} heights given for NC = {}\n", heights.size(), kNc);
    return 2;
  }
  int total = 0;
  for (int h : heights) total += h;

  const size_t want_bytes = (static_cast<size_t>(total) * kL + 31) / 32 * 4;
  if (sizeof(t->bits) != want_bytes && !(want_bytes <= 8 && sizeof(t->bits) <= 8)) {
    fmt::print(stderr, "tb_bitheap: bits port has {} bytes, the heights need {}\n", sizeof(t->bits), want_bytes);
    return 2;
  }

  std::mt19937 rng(0xb17ea9u);
  const uint32_t mask = kNc >= 32 ? ~0u : (1u << kNc) - 1;
  for (int round = 0; round < 300; ++round) {
    const unsigned density = round % 3 == 0 ? 8 : round % 3 == 1 ? 248 : 128;
    std::vector<uint32_t> want(kL, 0);
    int bit = 0;  // column c's bits follow column c-1's, plane by plane
    for (int c = 0; c < kNc; ++c) {
      for (int k = 0; k < heights[c]; ++k, ++bit) {
        for (int l = 0; l < kL; ++l) {
          const bool v = (rng() & 255) < density;
          sm::test::set_port_bit(t->bits, bit * kL + l, v);
          if (v) want[l] += 1u << c;
        }
      }
    }
    t->eval();
    for (int l = 0; l < kL; ++l) {
      uint32_t a = 0, b = 0;
      for (int c = 0; c < kNc; ++c) {
        a |= sm::test::port_bits(t->row_a, c * kL + l, 1) << c;
        b |= sm::test::port_bits(t->row_b, c * kL + l, 1) << c;
      }
      t.check(((a + b) & mask) == (want[l] & mask),
              [&] { return fmt::format("round {} lane {}: {} + {} want {}", round, l, a, b, want[l]); });
    }
  }
  return t.finish(fmt::format("tb_bitheap NC={} L={} heap of {} bits (lanes)", kNc, kL, total));
}
