#include "sm_window_support.hpp"

#include <cstdlib>

namespace sm::tools {

std::vector<uint16_t> offset_support(const OutImage& words, const std::vector<Offset>& offs, int tol) {
  std::vector<uint16_t> n(words.px.size(), 0);
  for (int y = 0; y < words.h; ++y)
    for (int x = 0; x < words.w; ++x) {
      const uint32_t c = words.at(x, y);
      if (!out_valid(c)) continue;
      uint16_t k = 0;
      for (const Offset& o : offs) {
        const int yy = y + o.dy, xx = x + o.dx;
        if (yy < 0 || yy >= words.h || xx < 0 || xx >= words.w) continue;
        const uint32_t v = words.at(xx, yy);
        k += out_valid(v) && std::abs(static_cast<int>(out_q4(v)) - static_cast<int>(out_q4(c))) <= tol;
      }
      n[static_cast<size_t>(y) * words.w + x] = k;
    }
  return n;
}

std::vector<Offset> row_offsets(int reach, int step) {
  std::vector<Offset> o;
  for (int dx = step; dx <= reach; dx += step) {
    o.push_back({0, -dx});
    o.push_back({0, dx});
  }
  return o;
}

std::vector<Offset> ring_offsets(int r, bool rows_above_only) {
  std::vector<Offset> o;
  for (int dy = -r; dy <= (rows_above_only ? 0 : r); dy += r)
    for (int dx = -r; dx <= r; dx += r)
      if (dy || dx) o.push_back({dy, dx});
  return o;
}

}  // namespace sm::tools
