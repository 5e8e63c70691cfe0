// Direct test of sm_udiv (the output stage's one divider): every (n, d) of the NW-bit
// dividend and DW-bit divisor in a shuffled order, with random ce gaps and garbage on the
// idle clocks, against its definition q = min(floor(n / d), 2^QW - 1) (2^QW - 1 for
// d = 0), QW ce's later; the outputs must not move without ce. Both users' shapes are
// exercised through them (tb_subpix_fit, tb_conf_ratio); this one checks the contract at
// the inputs they never give (d = 0, dividends far above 2^QW d).
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <random>
#include <utility>
#include <vector>

#include SM_VTOP_H
#include "sm_block_test.hpp"

namespace {
constexpr int kNw = SM_P_NW;
constexpr int kDw = SM_P_DW;
constexpr int kQw = SM_P_QW;
constexpr int kLatency = kQw;  // rtl/sm_udiv.v LATENCY

uint32_t quotient(uint32_t n, uint32_t d) {
  const uint32_t qmax = (1u << kQw) - 1;
  return d == 0 ? qmax : std::min(n / d, qmax);
}
}  // namespace

int main(int argc, char** argv) {
  static_assert(kNw + kDw <= 24, "every pair is tried");
  sm::test::BlockTest<SM_VTOP> t{"sm_udiv direct test"};
  int idle = 30;
  t.option("--idle", idle, "percent of clocks without ce").range(0, 90);
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::vector<std::pair<uint32_t, uint32_t>> vecs;
  for (uint32_t n = 0; n < (1u << kNw); ++n)
    for (uint32_t d = 0; d < (1u << kDw); ++d) vecs.emplace_back(n, d);
  std::mt19937 rng(0xd1u + kNw * 64 + kDw);
  std::shuffle(vecs.begin(), vecs.end(), rng);

  t.ce_schedule(77, idle);
  auto& top = t.tb().top();
  std::deque<std::pair<uint32_t, uint32_t>> pipe;
  size_t next = 0, done = 0;
  uint32_t last = top.q;
  long saturated = 0, by_zero = 0;
  while (done < vecs.size()) {
    const bool ce = t.next_ce();
    using Pair = std::pair<uint32_t, uint32_t>;
    const Pair garbage{static_cast<uint32_t>(rng()) & ((1u << kNw) - 1),
                       static_cast<uint32_t>(rng()) & ((1u << kDw) - 1)};
    const Pair v = ce && next < vecs.size() ? vecs[next] : garbage;
    top.n = v.first;
    top.d = v.second;
    t.tick();
    if (!ce) {
      t.check(top.q == last, [&] { return fmt::format("q moved without ce: {} -> {}", last, top.q); });
      continue;
    }
    last = top.q;
    if (next < vecs.size()) ++next;
    pipe.push_back(v);
    if (static_cast<int>(pipe.size()) < kLatency) continue;
    const auto [n, d] = pipe.front();
    pipe.pop_front();
    const uint32_t want = quotient(n, d);
    if (d == 0) ++by_zero;
    if (d != 0 && n / d > want) ++saturated;
    t.check(top.q == want, [&] { return fmt::format("n {} d {}: q {}, want {}", n, d, top.q, want); });
    ++done;
  }
  if (saturated == 0 || by_zero == 0) t.fail("no saturated quotient or no zero divisor: stimulus too weak");
  return t.finish(fmt::format("tb_udiv NW={} DW={} QW={}", kNw, kDw, kQw),
                  fmt::format(" ({} saturated, {} by 0)", saturated, by_zero));
}
