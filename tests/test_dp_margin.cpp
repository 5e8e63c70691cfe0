// Unit tests of the trellis min-marginals and the forward pass's excess costs
// (tools/sm_dp_margin.hpp) against independent truth: every path (and path prefix) of tiny
// lines enumerated, and the model's trellis (the optimal path's matched pixels have a
// min-marginal of 0).
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "dp.hpp"
#include "sm_dp_margin.hpp"

namespace {

using sm::tools::kNoPath;

// Every path (0, 0) -> (2n, 0), written from the definition (docs/algorithm.md 6): from
// (i - 1, d) a path goes to (i, d), or to an occlusion node (i, d +- 1) at the penalty of
// its left pixel; a matched node (i + d odd) adds the cost of left pixel (i - 1 + d) / 2.
// best[x * disp + d]: the cheapest path matching x at d; all: the cheapest of all.
struct Enumerate {
  const std::vector<uint8_t>& a;
  const std::vector<uint8_t>& pen;
  int n, disp;
  std::vector<int64_t> best;
  int64_t all = kNoPath;
  std::vector<int> matched;  // x * disp + d of the matched nodes on the current path

  void walk(int i, int d, int64_t cost) {
    if (i == 2 * n) {
      if (d != 0) return;
      all = std::min(all, cost);
      for (int k : matched) best[static_cast<size_t>(k)] = std::min(best[static_cast<size_t>(k)], cost);
      return;
    }
    for (int nd : {d, d - 1, d + 1}) {
      if (nd < 0 || nd >= disp) continue;
      if (i + 1 + nd > 2 * n) continue;  // level nd cannot come back to 0 by site 2n
      const bool occ = (i + 1 + nd) % 2 == 0;
      if (nd != d && !occ) continue;
      if (occ) {
        walk(i + 1, nd, cost + (nd != d ? pen[static_cast<size_t>((i + 1 + nd) / 2)] : 0));
        continue;
      }
      const int xl = (i + nd) / 2, xr = (i - nd) / 2;
      if (xr < 0 || xl >= n) continue;  // such a node never reaches the end node
      matched.push_back(xl * disp + nd);
      walk(i + 1, nd, cost + a[static_cast<size_t>(xl) * disp + nd]);
      matched.pop_back();
    }
  }
};

// Every path from (0, 0) up to site s, with no look at the end node (what a forward pass
// knows): u[i * disp + d], the cheapest path to (i, d); matched nodes beyond the line cost 0.
struct Prefixes {
  const std::vector<uint8_t>& a;
  const std::vector<uint8_t>& pen;
  int n, disp;
  std::vector<int64_t> u;

  void walk(int i, int d, int64_t cost) {
    int64_t& here = u[static_cast<size_t>(i) * disp + d];
    here = std::min(here, cost);
    if (i == 2 * n) return;
    for (int nd : {d, d - 1, d + 1}) {
      if (nd < 0 || nd >= disp) continue;
      const bool occ = (i + 1 + nd) % 2 == 0;
      if (nd != d && !occ) continue;
      const int xl = (i + nd) / 2;  // a matched node's left pixel
      const int64_t step = occ ? (nd != d ? pen[static_cast<size_t>(std::min((i + 1 + nd) / 2, n))] : 0)
                               : (xl < n ? a[static_cast<size_t>(xl) * disp + nd] : 0);
      walk(i + 1, nd, cost + step);
    }
  }
};

// A tiny line's costs (0..15) and occlusion penalties (0..11, n + 1 of them).
std::pair<std::vector<uint8_t>, std::vector<uint8_t>> random_line(std::mt19937& rng, int n, int disp) {
  std::vector<uint8_t> a(static_cast<size_t>(n) * disp), pen(static_cast<size_t>(n) + 1);
  for (auto& v : a) v = static_cast<uint8_t>(rng() % 16);
  for (auto& p : pen) p = static_cast<uint8_t>(rng() % 12);
  return {a, pen};
}

}  // namespace

TEST_CASE("dp_forward_excess equals exhaustive enumeration of path prefixes", "[dp_margin]") {
  std::mt19937 rng(2027);
  for (int disp : {2, 3, 4})
    for (int n = 1; n <= 4; ++n)
      for (int rep = 0; rep < 10; ++rep) {
        const auto [a, pen] = random_line(rng, n, disp);
        Prefixes p{a, pen, n, disp, std::vector<int64_t>(static_cast<size_t>(2 * n + 1) * disp, kNoPath)};
        p.walk(0, 0, 0);
        const std::vector<int64_t> e = sm::tools::dp_forward_excess(a.data(), n, pen.data(), disp);
        INFO("disp " << disp << " n " << n << " rep " << rep);
        for (int x = 0; x < n; ++x)
          for (int d = 0; d < disp; ++d) {
            const size_t k = static_cast<size_t>(x) * disp + d;
            if (d > 2 * x) {
              CHECK(e[k] == kNoPath);
              continue;
            }
            const int64_t* site = &p.u[static_cast<size_t>(2 * x + 1 - d) * disp];
            const int64_t best = *std::min_element(site, site + disp);
            CHECK(e[k] == (site[d] < kNoPath ? site[d] - best : kNoPath));
          }
      }
}

TEST_CASE("dp_min_marginals equal exhaustive enumeration", "[dp_margin]") {
  std::mt19937 rng(2026);
  for (int disp : {2, 3, 4})
    for (int n = 1; n <= 5; ++n)
      for (int rep = 0; rep < 20; ++rep) {
        const auto [a, pen] = random_line(rng, n, disp);
        Enumerate e{a, pen, n, disp, std::vector<int64_t>(a.size(), kNoPath), kNoPath, {}};
        e.walk(0, 0, 0);
        const std::vector<int64_t> m = sm::tools::dp_min_marginals(a.data(), n, pen.data(), disp);
        INFO("disp " << disp << " n " << n << " rep " << rep);
        REQUIRE(e.all < kNoPath);
        for (size_t k = 0; k < a.size(); ++k) CHECK(m[k] == (e.best[k] < kNoPath ? e.best[k] - e.all : kNoPath));
      }
}

TEST_CASE("dp_line_margins gives both cues of one forward pass", "[dp_margin]") {
  std::mt19937 rng(7);
  for (int rep = 0; rep < 20; ++rep) {
    const int n = 1 + static_cast<int>(rng() % 40), disp = 2 + static_cast<int>(rng() % 9);
    const auto [a, pen] = random_line(rng, n, disp);
    const sm::tools::LineMargins m = sm::tools::dp_line_margins(a.data(), n, pen.data(), disp);
    CHECK(m.min_marginal == sm::tools::dp_min_marginals(a.data(), n, pen.data(), disp));
    CHECK(m.forward_excess == sm::tools::dp_forward_excess(a.data(), n, pen.data(), disp));
  }
}

TEST_CASE("dp_min_marginals are 0 on the model trellis's matched pixels", "[dp_margin]") {
  std::mt19937 rng(99);
  sm::HwConfig hw;  // MAX_WIDTH 320, CENSUS 15 >> 2: CW 6
  hw.disp = 37;
  sm::DpScratch s;
  sm::DpLine line;
  const int n = 101;
  std::vector<uint8_t> a(static_cast<size_t>(n) * hw.disp), pen(static_cast<size_t>(n) + 1);
  for (auto& v : a) v = static_cast<uint8_t>(rng() % 64);
  for (auto& p : pen) p = static_cast<uint8_t>(20 + rng() % 40);
  sm::trellis_line_pen(a.data(), n, pen.data(), hw, s, line);
  const std::vector<int64_t> m = sm::tools::dp_min_marginals(a.data(), n, pen.data(), hw.disp);
  int matched = 0;
  for (int x = 0; x < n; ++x) {
    const int64_t* mx = &m[static_cast<size_t>(x) * hw.disp];
    CHECK(*std::min_element(mx, mx + hw.disp) >= 0);
    if (line.match[static_cast<size_t>(x)] < 0) continue;
    ++matched;
    CHECK(mx[line.match[static_cast<size_t>(x)]] == 0);
  }
  CHECK(matched > n / 2);
}

TEST_CASE("dp_margin: the cheapest match two levels away less the cheapest within one", "[dp_margin]") {
  const std::vector<int64_t> m = {9, 0, 3, 7, 5, kNoPath};
  CHECK(sm::tools::dp_margin(m.data(), 6, 1) == 5 - 0);        // near {9, 0, 3}, far {7, 5}
  CHECK(sm::tools::dp_margin(m.data(), 6, 4) == 0 - 5);        // near {7, 5}, far {9, 0, 3}
  const std::vector<int64_t> lone = {0, 4, kNoPath, kNoPath};  // nothing two levels away: sure
  CHECK(sm::tools::dp_margin(lone.data(), 4, 0) == kNoPath);
  CHECK(sm::tools::dp_margin(lone.data(), 4, 3) == -kNoPath);  // level 3 unreachable: no trust
}
