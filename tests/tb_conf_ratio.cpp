// Block test of sm_conf_ratio (docs/algorithm.md section 9.3, confidence bits 4:0): every
// (c1, c2) of the CW-bit costs, --passes times in a new shuffled order each, streamed with
// random ce gaps (tests/common/pipe_stream.hpp). For c1 <= c2 (every pair the WTA gives:
// c1 is the least cost) each result is compared with the model's confidence() bits 4:0 and
// with an independent reference in double arithmetic, min(31, floor(32 (c2 - c1) /
// (c2 + 1.0))); for c1 > c2, which the WTA cannot give, with the block's documented 0.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "confidence.hpp"
#include "pipe_stream.hpp"
#include "sm_block_test.hpp"

namespace {

constexpr int kCw = SM_P_CW;
constexpr int kMax = (1 << kCw) - 1;
constexpr int kLatency = 6;  // rtl/sm_conf_ratio.v LATENCY

struct Pair {
  uint8_t c1, c2;
};

// Independent truth for c1 <= c2.
int ratio_float(const Pair& p) {
  return static_cast<int>(std::min(31.0, std::floor(32.0 * (p.c2 - p.c1) / (p.c2 + 1.0))));
}

// The model's ratio: bits 4:0 of the confidence of a one-pixel evidence record.
int ratio_model(sm::Evidence& ev, const Pair& p) {
  ev.c1.at(0, 0) = p.c1;
  ev.c2.at(0, 0) = p.c2;
  return sm::confidence(ev, 0, 0, 0) & 31;
}

Pair random_pair(std::mt19937& rng) { return {static_cast<uint8_t>(rng() & kMax), static_cast<uint8_t>(rng() & kMax)}; }

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_conf_ratio block test"};
  int passes = 4;
  int idle = 30;
  unsigned seed = 1;
  t.option("--passes", passes, "times every pair is sent, each in a new order").range(1, 1000);
  t.option("--idle", idle, "percent of clocks without ce").range(0, 90);
  t.option("--seed", seed, "seed of the order, the ce gaps and the garbage");
  if (auto rc = t.parse(argc, argv)) return *rc;

  std::mt19937 rng(seed * 7919u + kCw);
  std::vector<Pair> all;
  for (int c1 = 0; c1 <= kMax; ++c1)
    for (int c2 = 0; c2 <= kMax; ++c2) all.push_back({static_cast<uint8_t>(c1), static_cast<uint8_t>(c2)});
  std::vector<Pair> vecs;
  for (int p = 0; p < passes; ++p) {
    std::shuffle(all.begin(), all.end(), rng);
    vecs.insert(vecs.end(), all.begin(), all.end());
  }

  sm::Evidence ev(1, 1);
  std::vector<long> seen(32, 0);  // results of the legal pairs
  long model_vs_float = 0, above = 0;
  const auto drive = [](SM_VTOP& top, const Pair& p) {
    top.s_c1 = p.c1;
    top.s_c2 = p.c2;
  };
  const auto out = [](SM_VTOP& top) { return static_cast<uint32_t>(top.m_ratio); };
  const auto check = [&](const Pair& p, uint32_t got) {
    const int r = static_cast<int>(got);
    if (p.c1 > p.c2) {
      ++above;
      t.check(r == 0, [&] { return fmt::format("c1 {} > c2 {}: RTL {}, want the documented 0", p.c1, p.c2, r); });
      return;
    }
    const int model = ratio_model(ev, p), ref = ratio_float(p);
    if (model != ref) ++model_vs_float;
    ++seen[static_cast<size_t>(std::clamp(r, 0, 31))];
    const auto msg = [&] {
      return fmt::format("c1 {} c2 {}: RTL {}, model {}, float reference {}", p.c1, p.c2, r, model, ref);
    };
    t.check(r == model, msg);
    t.check(r == ref, msg);
  };
  sm::test::stream_vectors(t, vecs, kLatency, seed, idle, random_pair, drive, out, check);

  // from CW 5 on every ratio 0..31 occurs (c2 = 31: the ratio is c2 - c1)
  for (int r = 0; r < 32 && kCw >= 5; ++r)
    if (seen[static_cast<size_t>(r)] == 0) t.fail(fmt::format("ratio {} never came out: stimulus too weak", r));
  if (above == 0) t.fail("no pair with c1 > c2");
  if (model_vs_float > 0) t.fail(fmt::format("the model differs from the float reference {} times", model_vs_float));
  return t.finish(fmt::format("tb_conf_ratio CW={} LATENCY={}", kCw, kLatency),
                  fmt::format(" ({} pairs, {} with c1 > c2)", vecs.size(), above));
}
