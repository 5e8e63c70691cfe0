#include "subpix.hpp"

#include <algorithm>
#include <cstdlib>

namespace sm {

int fit_q4(int cm, int c0, int cp, int fit) {
  const int num = cm - cp;
  const int den = fit == 0 ? 2 * (cm - 2 * c0 + cp) : 2 * std::max(cm - c0, cp - c0);
  if (den <= 0) return 0;
  // round(16 |num| / den), half up, on the magnitude (a 4-bit restoring division in the RTL)
  const int q = (32 * std::abs(num) + den) / (2 * den);
  const int m = std::min(q, 8);
  return num < 0 ? -m : m;
}

int subpix_q4(const Evidence& ev, int x, int y, int nd, const OutputRegs& r) {
  const int d = ev.d.at(x, y);
  if (!r.subpix_en) return 16 * d;
  if (r.subpix_src == 0) {
    if (d == 0 || d == nd - 1) return 16 * d;
    return 16 * d + fit_q4(ev.cm.at(x, y), ev.c0.at(x, y), ev.cp.at(x, y), r.subpix_fit);
  }
  const int dw = ev.dw.at(x, y);
  if (r.subpix_src == 1) {
    if (std::abs(d - dw) > 1 || dw == 0 || dw == nd - 1) return 16 * d;
    return 16 * dw + fit_q4(ev.band[1].at(x, y), ev.band[2].at(x, y), ev.band[3].at(x, y), r.subpix_fit);
  }
  const int j = d - dw + 2;  // d's index in the band
  if (j < 1 || j > 3 || d == 0 || d == nd - 1) return 16 * d;
  const auto b = [&](int k) { return static_cast<int>(ev.band[static_cast<size_t>(k)].at(x, y)); };
  return 16 * d + fit_q4(b(j - 1), b(j), b(j + 1), r.subpix_fit);
}

int subpix_after_post(int v, int d, int post_d) { return post_d == d ? v : 16 * post_d; }

}  // namespace sm
