// Unit tests of the trellis DP model (docs/algorithm.md, section 6) against
// independent truth: exhaustive path enumeration on tiny lines, and hand-built cost
// volumes whose optimal matching is known.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "dp.hpp"

namespace {

sm::HwConfig tiny_hw(int disp) {
  sm::HwConfig hw;
  hw.max_width = 16;
  hw.disp = disp;
  hw.census = 7;  // CW = 4
  hw.cost_shift = 2;
  return hw;
}

// Exhaustive search over all monotone paths (0,0) -> (2N,0) of the trellis, written
// directly from the definition: at site i the level d may stay, or -- only when the
// node (i, d) is an occlusion node -- come from d-1 or d+1 at an occlusion cost. The
// winner is the cheapest path; among equal costs the one whose choices, read from the
// end backwards, are lexicographically smallest (0 = same level, 1 = from d-1, 2 = from
// d+1), which is what "first choice reaching the minimum" at every node amounts to.
struct Brute {
  const std::vector<uint8_t>& a;  // a[x * disp + d]
  int n, disp, occ;
  std::vector<int> path, best_path;
  std::vector<int> key, best_key;  // choice per site, i = 2N first
  long best = -1;
  long n_best = 0;                        // paths reaching the best cost
  const std::vector<int>* pen = nullptr;  // per-pixel penalty of the occlusion nodes, by xl = (i + d) / 2

  void run() {
    path.assign(2 * n + 1, 0);
    go(1, 0, 0);
  }
  void go(int i, int dprev, long cost) {
    if (i > 2 * n) {
      if (dprev != 0) return;
      std::vector<int> k;
      for (int s = 2 * n; s >= 1; --s) {
        const int dd = path[s], dp = path[s - 1];
        k.push_back(dp == dd ? 0 : dp == dd - 1 ? 1 : 2);
      }
      if (best < 0 || cost < best) n_best = 0;
      if (best < 0 || cost <= best) ++n_best;
      if (best < 0 || cost < best || (cost == best && k < best_key)) {
        best = cost;
        best_key = k;
        best_path = path;
      }
      return;
    }
    for (int d = std::max(0, dprev - 1); d <= std::min(disp - 1, dprev + 1); ++d) {
      const bool matched = ((i + d) & 1) != 0;
      if (matched && d != dprev) continue;  // matched nodes only continue their level
      long c = cost;
      if (matched) {
        const int xl = (i - 1 + d) / 2;
        if (xl >= n || (i - 1 - d) < 0) continue;  // beyond the line: cannot end at 0
        c += a[static_cast<size_t>(xl) * disp + d];
      } else if (d != dprev) {
        c += pen ? (*pen)[static_cast<size_t>(std::min((i + d) / 2, n))] : occ;
      }
      path[i] = d;
      go(i + 1, d, c);
    }
  }
};

}  // namespace

TEST_CASE("trellis_dp: ACC_W matches the spec at the paper configuration", "[dp]") {
  sm::HwConfig hw;  // defaults: MAX_WIDTH 320, CENSUS 15, COST_SHIFT 2 -> CW 6
  REQUIRE(hw.cost_bits() == 6);
  CHECK(sm::dp_acc_bits(hw) == 19);
}

TEST_CASE("trellis_dp: optimal path and tie order equal exhaustive enumeration", "[dp]") {
  std::mt19937 rng(12345);
  int cases = 0, ties = 0;
  for (int disp : {2, 4}) {
    const sm::HwConfig hw = tiny_hw(disp);
    sm::DpScratch s;
    sm::DpLine line;
    for (int n = 1; n <= 5; ++n) {
      for (int rep = 0; rep < 60; ++rep) {
        // small ranges make many equal-cost paths, so the tie order is exercised
        const int top = rep % 3 == 0 ? 15 : rep % 3 == 1 ? 3 : 1;
        const int occ = static_cast<int>(rng() % (rep % 2 ? 4 : 20));
        std::vector<uint8_t> a(static_cast<size_t>(n) * disp);
        for (auto& v : a) v = static_cast<uint8_t>(rng() % (top + 1));
        Brute b{a, n, disp, occ, {}, {}, {}, {}, -1, 0};
        b.run();
        sm::trellis_line(a.data(), n, static_cast<uint8_t>(occ), hw, s, line);
        INFO("disp " << disp << " n " << n << " rep " << rep << " occ " << occ);
        REQUIRE(b.best >= 0);
        CHECK(static_cast<long>(line.end_cost) == b.best);
        CHECK(line.path == b.best_path);
        // disp(x) recorded at the path's matched nodes
        std::vector<int> match(n, -1);
        for (int i = 1; i <= 2 * n; ++i)
          if ((i + b.best_path[i]) & 1) match[(i - 1 + b.best_path[i]) / 2] = b.best_path[i];
        CHECK(line.match == match);
        ++cases;
        if (b.n_best > 1) ++ties;  // several optimal paths: the tie order decided
      }
    }
  }
  CHECK(cases == 600);
  CHECK(ties > 100);
}

TEST_CASE("trellis_dp: equal costs: choice 0 wins ties, all matched at 0", "[dp]") {
  // occ = 0, costs 0: every path costs 0; choice 0 everywhere keeps level 0.
  // costs 3, occ 7: each skipped pixel needs two diagonals (14 > 3), so all match at 0.
  const sm::HwConfig hw = tiny_hw(4);
  sm::DpScratch s;
  sm::DpLine line;
  for (auto [cost, occ] : std::vector<std::pair<int, int>>{{0, 0}, {3, 7}}) {
    std::vector<uint8_t> a(5 * 4, static_cast<uint8_t>(cost));
    sm::trellis_line(a.data(), 5, static_cast<uint8_t>(occ), hw, s, line);
    CHECK(line.match == std::vector<int>{0, 0, 0, 0, 0});
    CHECK(line.end_cost == 5u * cost);
  }
}

TEST_CASE("trellis_dp: three-way tie picks choice 0, a 1-vs-2 tie picks choice 1", "[dp]") {
  // N = 2, DISP = 4, occ = 0, all costs 0 except A(0,0) = A(1,0) = 9. Hand trellis:
  // (1,1) <- (0,0) (choice 1, U = 0); (2,0) <- (1,1) (choice 2, U = 0; from (1,0) costs
  // 9); (2,1) matched x = 1: U = A(1,1); (2,2) <- (1,1) (choice 1, U = 0); (3,0) matched
  // x = 1: U = 9; (3,1) occlusion: choice 0 = U(2,1), choice 1 = U(2,0) = 0, choice 2 =
  // U(2,2) = 0; (4,0) <- (3,1) (choice 2, 0 < 9).
  const sm::HwConfig hw = tiny_hw(4);
  std::vector<uint8_t> a(2 * 4, 0);
  a[0 * 4 + 0] = 9;
  a[1 * 4 + 0] = 9;
  sm::DpScratch s;
  sm::DpLine line;
  // A(1,1) = 0: three-way tie at (3,1), choice 0 -> pixel 1 matched at 1
  sm::trellis_line(a.data(), 2, 0, hw, s, line);
  CHECK(line.end_cost == 0u);
  CHECK(line.path == std::vector<int>{0, 1, 1, 1, 0});
  CHECK(line.match == std::vector<int>{-1, 1});
  CHECK(line.disp == std::vector<sm::DispPix>{0x8001, 0x8001});  // left of first: disp(first)
  // A(1,1) = 9: choice 1 (from (2,0)) and choice 2 (from (2,2)) tie -> choice 1
  a[1 * 4 + 1] = 9;
  sm::trellis_line(a.data(), 2, 0, hw, s, line);
  CHECK(line.end_cost == 0u);
  CHECK(line.path == std::vector<int>{0, 1, 0, 1, 0});
  CHECK(line.match == std::vector<int>{-1, -1});
  CHECK(line.disp == std::vector<sm::DispPix>{0x8000, 0x8000});  // no match: 0
}

namespace {
// A(x, d) = 0 at the true disparity (where x - d >= 0), `high` elsewhere.
sm::CostVolume ideal_volume(const std::vector<int>& dt, int disp, const std::vector<int>& bad = {}, int high = 15) {
  const int n = static_cast<int>(dt.size());
  sm::CostVolume v(n, 1, disp);
  for (int x = 0; x < n; ++x)
    for (int d = 0; d < disp; ++d) {
      const bool good = d == dt[x] && x - d >= 0 && std::find(bad.begin(), bad.end(), x) == bad.end();
      v.at(x, 0, d) = static_cast<uint8_t>(good ? 0 : high);
    }
  return v;
}
}  // namespace

TEST_CASE("trellis_dp: constant disparity everywhere, border pixels filled", "[dp]") {
  sm::HwConfig hw = tiny_hw(16);
  hw.max_width = 64;
  for (int d0 : {0, 1, 5, 8, 15}) {
    const auto v = ideal_volume(std::vector<int>(40, d0), 16);
    sm::DpScratch s;
    sm::DpLine line;
    sm::trellis_line(v.pix(0, 0), 40, 4, hw, s, line);
    for (int x = 0; x < 40; ++x) {
      INFO("d0 " << d0 << " x " << x);
      CHECK(line.match[x] == (x < d0 ? -1 : d0));  // the leftmost d0 pixels are occluded
    }
    const auto img = sm::trellis_dp(v, 4, hw);
    for (int x = 0; x < 40; ++x) CHECK(img.at(x, 0) == (0x8000 | d0));
  }
}

TEST_CASE("trellis_dp: step up: occluded background pixels, background fill", "[dp]") {
  sm::HwConfig hw = tiny_hw(16);
  hw.max_width = 64;
  const int n = 48, xs = 24;
  for (auto [d1, d2] : std::vector<std::pair<int, int>>{{2, 9}, {0, 5}, {3, 4}, {1, 15}}) {
    std::vector<int> dt(n);
    for (int x = 0; x < n; ++x) dt[x] = x < xs ? d1 : d2;
    // background pixels xs-(d2-d1)..xs-1 are hidden by the foreground in the right
    // image: no good match anywhere
    std::vector<int> hidden;
    for (int x = xs - (d2 - d1); x < xs; ++x) hidden.push_back(x);
    const auto v = ideal_volume(dt, 16, hidden);
    sm::DpScratch s;
    sm::DpLine line;
    sm::trellis_line(v.pix(0, 0), n, 3, hw, s, line);
    for (int x = 0; x < n; ++x) {
      INFO("d1 " << d1 << " d2 " << d2 << " x " << x);
      const bool occluded = x < d1 || (x >= xs - (d2 - d1) && x < xs);
      CHECK(line.match[x] == (occluded ? -1 : dt[x]));
      CHECK(line.disp[x] == (0x8000 | dt[x]));  // background fill = d1, foreground d2
    }
  }
}

TEST_CASE("trellis_dp: step down (foreground left): every left pixel matched", "[dp]") {
  sm::HwConfig hw = tiny_hw(16);
  hw.max_width = 64;
  const int n = 40, xs = 20;
  std::vector<int> dt(n);
  for (int x = 0; x < n; ++x) dt[x] = x < xs ? 9 : 2;
  const auto v = ideal_volume(dt, 16);
  sm::DpScratch s;
  sm::DpLine line;
  sm::trellis_line(v.pix(0, 0), n, 3, hw, s, line);
  for (int x = 0; x < n; ++x) CHECK(line.match[x] == (x < 9 ? -1 : dt[x]));
}

TEST_CASE("trellis_dp: fill rule on hand-made match lists", "[dp]") {
  std::vector<sm::DispPix> out;
  sm::dp_fill({-1, -1, 5, -1, -1, 2, 7, -1, 3, -1}, out);
  CHECK(out ==
        std::vector<sm::DispPix>{0x8005, 0x8005, 0x8005, 0x8002, 0x8002, 0x8002, 0x8007, 0x8003, 0x8003, 0x8003});
  sm::dp_fill({-1, -1, -1}, out);
  CHECK(out == std::vector<sm::DispPix>{0x8000, 0x8000, 0x8000});
}

TEST_CASE("trellis_dp: rejects a volume of the wrong depth", "[dp]") {
  const sm::HwConfig hw = tiny_hw(16);
  CHECK_THROWS_AS(sm::trellis_dp(sm::CostVolume(8, 2, 8), 5, hw), std::invalid_argument);
}

// ---- per-pixel penalties (trellis_line with pen, the edge-dependent penalty study) ----

namespace {

// The recurrence of docs/algorithm.md section 6 site by site, with the penalty of the
// occlusion node (i, d) taken from pen[(i + d) / 2]: an independent (scalar, level by
// level) reference for lines too long to enumerate.
std::vector<int> ref_dp_pen(const std::vector<uint8_t>& a, int n, int disp, const std::vector<int>& pen,
                            long* end_cost) {
  const long big = 1L << 40;
  std::vector<long> u(disp, big), v(disp);
  u[0] = 0;
  std::vector<std::vector<int>> ch(2 * n + 1, std::vector<int>(disp, 0));
  for (int i = 1; i <= 2 * n; ++i) {
    for (int d = 0; d < disp; ++d) {
      if ((i + d) & 1) {
        const int xl = (i - 1 + d) / 2;
        v[d] = u[d] + (xl < n ? a[static_cast<size_t>(xl) * disp + d] : 0);
      } else {
        const long p = pen[static_cast<size_t>(std::min((i + d) / 2, n))];
        long best = u[d];
        int c = 0;
        if (d >= 1 && u[d - 1] + p < best) best = u[d - 1] + p, c = 1;
        if (d + 1 < disp && u[d + 1] + p < best) best = u[d + 1] + p, c = 2;
        v[d] = best;
        ch[i][d] = c;
      }
    }
    std::swap(u, v);
  }
  *end_cost = u[0];
  std::vector<int> path(2 * n + 1, 0);
  int d = 0;
  for (int i = 2 * n; i >= 1; --i) {
    path[i] = d;
    if (!((i + d) & 1)) d += ch[i][d] == 1 ? -1 : ch[i][d] == 2 ? 1 : 0;
  }
  path[0] = d;
  return path;
}

}  // namespace

TEST_CASE("trellis_dp: per-pixel penalties equal exhaustive enumeration", "[dp]") {
  std::mt19937 rng(777);
  int cases = 0;
  for (int disp : {2, 4}) {
    const sm::HwConfig hw = tiny_hw(disp);
    sm::DpScratch s;
    sm::DpLine line;
    for (int n = 1; n <= 5; ++n)
      for (int rep = 0; rep < 40; ++rep) {
        const int top = rep % 2 ? 15 : 3;
        std::vector<uint8_t> a(static_cast<size_t>(n) * disp);
        for (auto& v : a) v = static_cast<uint8_t>(rng() % (top + 1));
        std::vector<int> pen(static_cast<size_t>(n) + 1);
        for (auto& p : pen) p = static_cast<int>(rng() % (rep % 3 ? 6 : 20));
        std::vector<uint8_t> pen8(pen.begin(), pen.end());
        Brute b{a, n, disp, 0, {}, {}, {}, {}, -1, 0, &pen};
        b.run();
        sm::trellis_line_pen(a.data(), n, pen8.data(), hw, s, line);
        INFO("disp " << disp << " n " << n << " rep " << rep);
        REQUIRE(b.best >= 0);
        CHECK(static_cast<long>(line.end_cost) == b.best);
        CHECK(line.path == b.best_path);
        ++cases;
      }
  }
  CHECK(cases == 400);
}

TEST_CASE("trellis_dp: per-pixel penalties on long lines (vector lanes) equal the recurrence", "[dp]") {
  std::mt19937 rng(4242);
  for (int disp : {16, 37, 64}) {
    sm::HwConfig hw;
    hw.max_width = 96;
    hw.disp = disp;
    sm::DpScratch s;
    sm::DpLine line, uni;
    for (int rep = 0; rep < 6; ++rep) {
      const int n = 40 + static_cast<int>(rng() % 57);
      std::vector<uint8_t> a(static_cast<size_t>(n) * disp);
      for (auto& v : a) v = static_cast<uint8_t>(rng() % 64);
      std::vector<int> pen(static_cast<size_t>(n) + 1);
      for (auto& p : pen) p = rng() % 2 ? 3 : 11;
      std::vector<uint8_t> pen8(pen.begin(), pen.end());
      long end = 0;
      const std::vector<int> path = ref_dp_pen(a, n, disp, pen, &end);
      sm::trellis_line_pen(a.data(), n, pen8.data(), hw, s, line);
      INFO("disp " << disp << " n " << n << " rep " << rep);
      CHECK(static_cast<long>(line.end_cost) == end);
      CHECK(line.path == path);
      // One penalty everywhere: the per-pixel form is the uniform trellis bit for bit.
      std::vector<uint8_t> flat(static_cast<size_t>(n) + 1, 9);
      sm::trellis_line_pen(a.data(), n, flat.data(), hw, s, line);
      sm::trellis_line(a.data(), n, static_cast<uint8_t>(9), hw, s, uni);
      CHECK(line.path == uni.path);
      CHECK(line.disp == uni.disp);
    }
  }
}

TEST_CASE("edge_penalties: occ_edge where the left image steps by more than edge_t", "[dp]") {
  // |dI| of x = 1..5: 16, 17, 0, 40, 15; edge_t 16 -> edges at x = 2 and 4; x = 0 and x = n never.
  const std::vector<uint8_t> left = {100, 116, 133, 133, 93, 108};
  std::vector<uint8_t> pen;
  sm::edge_penalties(left.data(), 6, 11, 7, 16, pen);
  CHECK(pen == std::vector<uint8_t>{11, 11, 7, 11, 7, 11, 11});
  sm::edge_penalties(left.data(), 6, 11, 7, 0, pen);
  CHECK(pen == std::vector<uint8_t>{11, 7, 7, 11, 7, 7, 11});
}
