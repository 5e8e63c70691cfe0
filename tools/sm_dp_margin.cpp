#include "sm_dp_margin.hpp"

#include <algorithm>
#include <cstdlib>

namespace sm::tools {

namespace {

// Node (i, d) of sites 0..2n (algorithm.md 6): matched when i + d is odd, pairing left pixel
// (i - 1 + d) / 2 with its cost (0 beyond the line, as the model's trellis_line); an
// occlusion node otherwise, reached diagonally at the penalty of its left pixel (i + d) / 2.
// pen has n + 1 entries; a node whose left pixel is beyond n never reaches the end node and
// takes pen[n], as the model's trellis_line_pen pads it.
struct Trellis {
  const uint8_t* agg;
  int n, disp;
  const uint8_t* pen;
  int64_t cost(int i, int d) const {
    const int xl = (i - 1 + d) / 2;
    return xl < n ? agg[static_cast<size_t>(xl) * disp + d] : 0;
  }
  int64_t diag(int i, int d) const { return pen[std::min((i + d) / 2, n)]; }
};

int64_t add(int64_t a, int64_t b) { return a >= kNoPath ? kNoPath : std::min(kNoPath, a + b); }

// U(i, d): the cheapest path from (0, 0) to (i, d), its node costs included.
std::vector<int64_t> forward(const Trellis& t) {
  const int s = 2 * t.n, nd = t.disp;
  std::vector<int64_t> u(static_cast<size_t>(s + 1) * nd, kNoPath);
  u[0] = 0;
  for (int i = 1; i <= s; ++i) {
    const int64_t* p = &u[static_cast<size_t>(i - 1) * nd];
    int64_t* c = &u[static_cast<size_t>(i) * nd];
    for (int d = 0; d < nd; ++d) {
      if ((i + d) & 1) {
        c[d] = add(p[d], t.cost(i, d));
        continue;
      }
      c[d] = p[d];
      if (d >= 1) c[d] = std::min(c[d], add(p[d - 1], t.diag(i, d)));
      if (d + 1 < nd) c[d] = std::min(c[d], add(p[d + 1], t.diag(i, d)));
    }
  }
  return u;
}

// V(i, d): the cheapest path from (i, d) to the end node (2n, 0), (i, d)'s own cost excluded.
std::vector<int64_t> backward(const Trellis& t) {
  const int s = 2 * t.n, nd = t.disp;
  std::vector<int64_t> v(static_cast<size_t>(s + 1) * nd, kNoPath);
  v[static_cast<size_t>(s) * nd] = 0;
  for (int i = s; i >= 1; --i) {
    const int64_t* c = &v[static_cast<size_t>(i) * nd];
    int64_t* p = &v[static_cast<size_t>(i - 1) * nd];
    for (int d = 0; d < nd; ++d) {
      if (!((i + d) & 1)) {  // (i, d) is an occlusion node: choice 0 only
        p[d] = c[d];
        continue;
      }
      p[d] = add(c[d], t.cost(i, d));  // the matched node, then the two diagonals
      if (d + 1 < nd) p[d] = std::min(p[d], add(c[d + 1], t.diag(i, d + 1)));
      if (d >= 1) p[d] = std::min(p[d], add(c[d - 1], t.diag(i, d - 1)));
    }
  }
  return v;
}

// M(x, d) from the forward costs u and the backward costs of t.
std::vector<int64_t> min_marginals(const Trellis& t, const std::vector<int64_t>& u) {
  const std::vector<int64_t> v = backward(t);
  const int64_t best = u[static_cast<size_t>(2 * t.n) * t.disp];
  std::vector<int64_t> m(static_cast<size_t>(t.n) * t.disp, kNoPath);
  for (int x = 0; x < t.n; ++x)
    for (int d = 0; d < t.disp && d <= 2 * x; ++d) {
      const size_t k = static_cast<size_t>(2 * x + 1 - d) * t.disp + d;
      const int64_t through = add(u[k], v[k]);
      if (through < kNoPath) m[static_cast<size_t>(x) * t.disp + d] = through - best;
    }
  return m;
}

// E(x, d) from the forward costs u.
std::vector<int64_t> forward_excess(const Trellis& t, const std::vector<int64_t>& u) {
  std::vector<int64_t> e(static_cast<size_t>(t.n) * t.disp, kNoPath);
  for (int x = 0; x < t.n; ++x)
    for (int d = 0; d < t.disp && d <= 2 * x; ++d) {
      const int64_t* site = &u[static_cast<size_t>(2 * x + 1 - d) * t.disp];
      const int64_t best = *std::min_element(site, site + t.disp);
      if (site[d] < kNoPath) e[static_cast<size_t>(x) * t.disp + d] = site[d] - best;
    }
  return e;
}

}  // namespace

std::vector<int64_t> dp_min_marginals(const uint8_t* agg, int n, const uint8_t* pen, int disp) {
  const Trellis t{agg, n, disp, pen};
  return min_marginals(t, forward(t));
}

std::vector<int64_t> dp_forward_excess(const uint8_t* agg, int n, const uint8_t* pen, int disp) {
  const Trellis t{agg, n, disp, pen};
  return forward_excess(t, forward(t));
}

LineMargins dp_line_margins(const uint8_t* agg, int n, const uint8_t* pen, int disp) {
  const Trellis t{agg, n, disp, pen};
  const std::vector<int64_t> u = forward(t);
  return {min_marginals(t, u), forward_excess(t, u)};
}

int64_t dp_margin(const int64_t* m, int disp, int d) {
  int64_t near = kNoPath, far = kNoPath;
  for (int k = 0; k < disp; ++k) {
    int64_t& side = std::abs(k - d) <= 1 ? near : far;
    side = std::min(side, m[k]);
  }
  if (near >= kNoPath) return -kNoPath;
  return far >= kNoPath ? kNoPath : far - near;
}

}  // namespace sm::tools
