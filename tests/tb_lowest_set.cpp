// Direct test of sm_lowest_set (sm_objects' choice of the next free label): random
// vectors from a fixed seed at several densities, single bits at every position and
// the empty vector; `any` and `idx` are checked against the definition (the lowest set
// bit). Configurations cover one tier (N <= 8), two (N <= 64, N not a multiple of 8) and
// three (N > 64).
#include <fmt/format.h>

#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "sm_block_test.hpp"
#include "sm_port.hpp"

int main(int argc, char** argv) {
  constexpr int kN = SM_P_N;
  sm::test::BlockTest<SM_VTOP> t{"sm_lowest_set direct test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(0x10e5e7u);
  auto check = [&](const std::vector<bool>& v, const std::string& what) {
    for (int i = 0; i < kN; ++i) sm::test::set_port_bit(t->v, i, v[i]);
    t->eval();
    int want = -1;
    for (int i = kN - 1; i >= 0; --i)
      if (v[i]) want = i;
    const bool any = t->any;
    const int idx = static_cast<int>(t->idx);
    t.check(any == (want >= 0) && (want < 0 || idx == want),
            [&] { return fmt::format("{}: any {} idx {}, want lowest set bit {}", what, any, idx, want); });
  };
  check(std::vector<bool>(kN, false), "empty");
  for (int b = 0; b < kN; ++b) {
    std::vector<bool> v(kN, false);
    v[b] = true;
    check(v, fmt::format("bit {} alone", b));
    for (int i = b; i < kN; ++i) v[i] = (rng() & 1) != 0;  // and random bits above it
    v[b] = true;
    check(v, fmt::format("bit {} with random bits above", b));
  }
  for (int round = 0; round < 3000; ++round) {
    const unsigned density = round % 3 == 0 ? 2 : round % 3 == 1 ? 128 : 250;  // of 256
    std::vector<bool> v(kN);
    for (int i = 0; i < kN; ++i) v[i] = (rng() & 255) < density;
    check(v, fmt::format("round {}", round));
  }
  return t.finish(fmt::format("tb_lowest_set N={}", kN));
}
