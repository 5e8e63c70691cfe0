// Block test of sm_subpix_fit (docs/algorithm.md section 9.1): every (cm, c0, cp, fit) of
// the CW-bit costs in a shuffled order (--random N: N random vectors instead, for CW 8),
// plus the corner values, streamed with random ce gaps (tests/common/pipe_stream.hpp).
// Each result is compared with the model's fit_q4 and with an independent reference
// computed here in double arithmetic (16 num / den rounded half away from zero, clamped to
// +-8), so a bug the model and the RTL share shows too. The stimulus must reach the
// cases that matter: no fit (den <= 0), the clamp, and (CW >= 5) exact ties of the rounding.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "pipe_stream.hpp"
#include "sm_block_test.hpp"
#include "subpix.hpp"

namespace {

constexpr int kCw = SM_P_CW;
constexpr int kMax = (1 << kCw) - 1;
constexpr int kLatency = 7;  // rtl/sm_subpix_fit.v LATENCY

struct Fit {
  uint8_t cm, c0, cp, fit;
};

// The definition in doubles: the fit's denominator and the offset of its minimum,
// 16 (cm - cp) / den (0 when den <= 0: no fit).
double fit_den(const Fit& v) {
  return v.fit == 0 ? 2.0 * (v.cm - 2.0 * v.c0 + v.cp) : 2.0 * std::max(v.cm - v.c0, v.cp - v.c0);
}
double fit_exact(const Fit& v) {
  const double den = fit_den(v);
  return den > 0 ? 16.0 * (v.cm - v.cp) / den : 0.0;
}

// Independent truth: round half away from zero (std::round), clamp to half a level.
int fit_float(const Fit& v) { return static_cast<int>(std::clamp(std::round(fit_exact(v)), -8.0, 8.0)); }

std::vector<Fit> all_vectors(std::mt19937& rng) {
  std::vector<Fit> v;
  for (int fit = 0; fit < 2; ++fit)
    for (int cm = 0; cm <= kMax; ++cm)
      for (int c0 = 0; c0 <= kMax; ++c0)
        for (int cp = 0; cp <= kMax; ++cp)
          v.push_back({static_cast<uint8_t>(cm), static_cast<uint8_t>(c0), static_cast<uint8_t>(cp),
                       static_cast<uint8_t>(fit)});
  std::shuffle(v.begin(), v.end(), rng);  // neighbours in the pipeline differ
  return v;
}

Fit random_fit(std::mt19937& rng) {
  return {static_cast<uint8_t>(rng() & kMax), static_cast<uint8_t>(rng() & kMax), static_cast<uint8_t>(rng() & kMax),
          static_cast<uint8_t>(rng() & 1)};
}

// Every combination of 0, 1, 2, max/2, max-1 and max (the extremes of each width).
std::vector<Fit> corner_vectors() {
  std::vector<int> c{0, 1, 2, kMax / 2, kMax - 1, kMax};
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  c.erase(std::remove_if(c.begin(), c.end(), [](int x) { return x < 0 || x > kMax; }), c.end());
  std::vector<Fit> v;
  for (int fit = 0; fit < 2; ++fit)
    for (int cm : c)
      for (int c0 : c)
        for (int cp : c)
          v.push_back({static_cast<uint8_t>(cm), static_cast<uint8_t>(c0), static_cast<uint8_t>(cp),
                       static_cast<uint8_t>(fit)});
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_subpix_fit block test"};
  long random = 0;
  int idle = 30;
  unsigned seed = 1;
  t.option("--random", random, "random vectors instead of every one (0: every one)").range(0, 1L << 30);
  t.option("--idle", idle, "percent of clocks without ce").range(0, 90);
  t.option("--seed", seed, "seed of the order, the ce gaps and the garbage");
  if (auto rc = t.parse(argc, argv)) return *rc;

  std::mt19937 rng(seed * 7919u + kCw);
  std::vector<Fit> vecs = corner_vectors();
  if (random > 0) {
    for (long i = 0; i < random; ++i) vecs.push_back(random_fit(rng));
  } else {
    const auto all = all_vectors(rng);
    vecs.insert(vecs.end(), all.begin(), all.end());
  }

  long no_fit = 0, clamped = 0, ties = 0, model_vs_float = 0;
  for (const Fit& v : vecs) {
    const double x = fit_exact(v);
    if (fit_den(v) <= 0 && v.cm != v.cp) ++no_fit;
    if (std::abs(x) > 8.0) ++clamped;
    if (std::abs(x) < 8.0 && std::abs(x - std::trunc(x)) == 0.5) ++ties;
  }

  const auto drive = [](SM_VTOP& top, const Fit& v) {
    top.s_cm = v.cm;
    top.s_c0 = v.c0;
    top.s_cp = v.cp;
    top.s_fit = v.fit;
  };
  const auto out = [](SM_VTOP& top) { return static_cast<uint32_t>(top.m_frac); };
  const auto check = [&](const Fit& v, uint32_t got) {
    const int f = static_cast<int>(got) >= 16 ? static_cast<int>(got) - 32 : static_cast<int>(got);
    const int model = sm::fit_q4(v.cm, v.c0, v.cp, v.fit), ref = fit_float(v);
    if (model != ref) ++model_vs_float;
    const auto msg = [&] {
      return fmt::format("cm {} c0 {} cp {} fit {}: RTL {}, model fit_q4 {}, float reference {} ({:.4f})", v.cm, v.c0,
                         v.cp, v.fit, f, model, ref, fit_exact(v));
    };
    t.check(f == model, msg);
    t.check(f == ref, msg);
  };
  sm::test::stream_vectors(t, vecs, kLatency, seed, idle, random_fit, drive, out, check);

  if (no_fit == 0) t.fail("no vector without a fit (den <= 0, num != 0): stimulus too weak");
  if (clamped == 0 && kCw >= 2) t.fail("no vector beyond the clamp: stimulus too weak");
  if (ties == 0 && kCw >= 5) t.fail("no exact tie of the rounding: stimulus too weak");
  if (model_vs_float > 0) t.fail(fmt::format("the model differs from the float reference {} times", model_vs_float));
  return t.finish(
      fmt::format("tb_subpix_fit CW={} LATENCY={}", kCw, kLatency),
      fmt::format(" ({} vectors: {} without a fit, {} clamped, {} ties)", vecs.size(), no_fit, clamped, ties));
}
