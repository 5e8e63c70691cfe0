#include "row_support.hpp"

#include <algorithm>
#include <cstdlib>

#include "parallel.hpp"

namespace sm {

int row_support(const OutImage& in, int x, int y) {
  const int c = static_cast<int>(out_q4(in.at(x, y)));
  int r = 0;
  for (int dx = -kRowSupportReach; dx <= kRowSupportReach; dx += kRowSupportStep) {
    const int xx = x + dx;
    if (dx == 0 || xx < 0 || xx >= in.w) continue;
    const uint32_t v = in.at(xx, y);
    r += out_valid(v) && std::abs(static_cast<int>(out_q4(v)) - c) <= kRowSupportTol;
  }
  return r;
}

OutImage row_support_output(const OutImage& in, int threads) {
  OutImage out(in.w, in.h);
  parallel_bands(in.h, threads, [&](int y0, int y1, int) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < in.w; ++x) {
        const uint32_t v = in.at(x, y);
        if (!out_valid(v)) {
          out.at(x, y) = v;
          continue;
        }
        const int c = static_cast<int>(out_conf(v)) + kRowSupportWeight * row_support(in, x, y);
        out.at(x, y) = make_out_word(true, static_cast<unsigned>(std::min(c, 255)), out_q4(v));
      }
  });
  return out;
}

}  // namespace sm
