#include "pre.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace sm {

Image8 brightness(const Image8& in, uint16_t gain, int16_t offset) {
  const int g = gain & 0x3ff;
  // 9-bit two's complement, as the register holds it
  const int off = ((offset & 0x1ff) ^ 0x100) - 0x100;
  // The formula for each of the 256 inputs once, then a table lookup per pixel.
  std::array<uint8_t, 256> lut;
  for (int p = 0; p < 256; ++p)
    lut[static_cast<size_t>(p)] = static_cast<uint8_t>(std::clamp(((p * g + 128) >> 8) + off, 0, 255));
  bool same = true;  // (speed: the default gain 1.0 and offset 0 map every value to itself)
  for (int p = 0; p < 256; ++p) same = same && lut[static_cast<size_t>(p)] == p;
  if (same) return in;
  Image8 out(in.w, in.h);
  for (size_t i = 0; i < in.px.size(); ++i) out.px[i] = lut[in.px[i]];
  return out;
}

namespace {

void check_grid(const RectGrid& g, int width, int height) {
  const int gw = RectGrid::points_w(width), gh = RectGrid::points_h(height);
  const size_t n = static_cast<size_t>(gw) * gh;
  if (g.gw != gw || g.gh != gh || g.sx.size() != n || g.sy.size() != n)
    throw std::invalid_argument(
        fmt::format("rectify: grid {}x{} ({} / {} points) does not fit a {}x{} image (needs {}x{})", g.gw, g.gh,
                    g.sx.size(), g.sy.size(), width, height, gw, gh));
}

// One coordinate of section 2: V0/V1 down the grid columns, then across; Q.13 -> Q.4.
int interp_q4(const std::vector<int16_t>& v, int gw, int x, int y) {
  const int gx = x >> kGridShift, fx = x & (kGridStep - 1);
  const int gy = y >> kGridShift, fy = y & (kGridStep - 1);
  auto p = [&](int cx, int cy) { return static_cast<int32_t>(v[static_cast<size_t>(cy) * gw + cx]); };
  const int32_t v0 = p(gx, gy) * (kGridStep - fy) + p(gx, gy + 1) * fy;          // Q.9
  const int32_t v1 = p(gx + 1, gy) * (kGridStep - fy) + p(gx + 1, gy + 1) * fy;  // Q.9
  const int32_t s = v0 * (kGridStep - fx) + v1 * fx;                             // Q.13
  return (s + 256) >> 9;                                                         // Q.4
}

}  // namespace

void rect_source_q4(const RectGrid& g, int x, int y, int& sx, int& sy) {
  sx = interp_q4(g.sx, g.gw, x, y);
  sy = interp_q4(g.sy, g.gw, x, y);
}

namespace {
// True when g is the identity grid of a w x h image and its points fit int16 unwrapped:
// every source position is then exactly (16 x, 16 y) in Q.4 (both fractions 0, the tap
// at (x, y) weighted 256/256), so rectify returns its input.
bool exact_identity(const RectGrid& g, int w, int h) {
  const int limit = 32767 >> kMapFrac;  // the largest grid coordinate in whole pixels
  if ((g.gw - 1) * kGridStep > limit || (g.gh - 1) * kGridStep > limit) return false;
  const RectGrid id = RectGrid::identity(w, h);
  return g.gw == id.gw && g.gh == id.gh && g.sx == id.sx && g.sy == id.sy;
}
}  // namespace

Image8 rectify(const Image8& in, const RectGrid& grid, bool enable, const HwConfig& hw) {
  const int w = in.w, h = in.h;
  if (!enable) return in;
  const RectGrid g = grid.gw == 0 ? RectGrid::identity(w, h) : grid;
  check_grid(g, w, h);
  if (exact_identity(g, w, h)) return in;  // (speed: the interpolation below gives the same bits)
  const int rr = hw.rect_radius;
  Image8 out(w, h);
  // interp_q4 with its column step (V0 / V1, Q.9) done once per grid point and row
  // instead of once per pixel: the same integer arithmetic, hoisted.
  std::vector<int32_t> vx(static_cast<size_t>(g.gw)), vy(static_cast<size_t>(g.gw));
  for (int y = 0; y < h; ++y) {
    const int gy = y >> kGridShift, fy = y & (kGridStep - 1);
    for (int gx = 0; gx < g.gw; ++gx) {
      const size_t p0 = static_cast<size_t>(gy) * g.gw + gx, p1 = p0 + g.gw;
      vx[static_cast<size_t>(gx)] = int32_t{g.sx[p0]} * (kGridStep - fy) + int32_t{g.sx[p1]} * fy;
      vy[static_cast<size_t>(gx)] = int32_t{g.sy[p0]} * (kGridStep - fy) + int32_t{g.sy[p1]} * fy;
    }
    for (int x = 0; x < w; ++x) {
      const size_t gx = static_cast<size_t>(x >> kGridShift);
      const int fx = x & (kGridStep - 1);
      const int sx = (vx[gx] * (kGridStep - fx) + vx[gx + 1] * fx + 256) >> 9;  // Q.13 -> Q.4
      const int sy = (vy[gx] * (kGridStep - fx) + vy[gx + 1] * fx + 256) >> 9;
      const int ix = sx >> 4, ax = sx & 15, iy = sy >> 4, ay = sy & 15;
      if (ix >= 0 && ix + 1 < w && iy >= 0 && iy + 1 < h && iy >= y - rr && iy + 1 <= y + rr) {
        // Every tap inside the image and the row window: no test per tap.
        const uint8_t* p = &in.px[static_cast<size_t>(iy) * w + ix];
        const int acc =
            p[0] * (16 - ax) * (16 - ay) + p[1] * ax * (16 - ay) + p[w] * (16 - ax) * ay + p[w + 1] * ax * ay + 128;
        out.at(x, y) = static_cast<uint8_t>(acc >> 8);
        continue;
      }
      auto tap = [&](int c, int r) -> int {
        if (c < 0 || c >= w || r < 0 || r >= h || r < y - rr || r > y + rr) return 0;
        return in.at(c, r);
      };
      const int acc = tap(ix, iy) * (16 - ax) * (16 - ay) + tap(ix + 1, iy) * ax * (16 - ay) +
                      tap(ix, iy + 1) * (16 - ax) * ay + tap(ix + 1, iy + 1) * ax * ay + 128;
      out.at(x, y) = static_cast<uint8_t>(acc >> 8);
    }
  }
  return out;
}

RectGrid grid_from_maps(const std::vector<float>& mapx, const std::vector<float>& mapy, int map_w, int map_h, int width,
                        int height) {
  RectGrid g;
  g.gw = RectGrid::points_w(width);
  g.gh = RectGrid::points_h(height);
  const int need_w = (g.gw - 1) * kGridStep + 1, need_h = (g.gh - 1) * kGridStep + 1;
  const size_t n = static_cast<size_t>(map_w) * map_h;
  if (map_w < need_w || map_h < need_h || mapx.size() != n || mapy.size() != n)
    throw std::invalid_argument(
        fmt::format("grid_from_maps: map {}x{} ({} / {} values) is smaller than the grid extent "
                    "{}x{} of a {}x{} image",
                    map_w, map_h, mapx.size(), mapy.size(), need_w, need_h, width, height));
  auto q5 = [](float v) -> int16_t {
    if (!std::isfinite(v)) throw std::invalid_argument("grid_from_maps: non-finite map value");
    const double s = std::round(static_cast<double>(v) * (1 << kMapFrac));
    return static_cast<int16_t>(std::clamp(s, -32768.0, 32767.0));
  };
  const size_t np = static_cast<size_t>(g.gw) * g.gh;
  g.sx.resize(np);
  g.sy.resize(np);
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx) {
      const size_t m = static_cast<size_t>(gy * kGridStep) * map_w + gx * kGridStep;
      g.sx[static_cast<size_t>(gy) * g.gw + gx] = q5(mapx[m]);
      g.sy[static_cast<size_t>(gy) * g.gw + gx] = q5(mapy[m]);
    }
  return g;
}

int rect_radius_needed(const RectGrid& g, int width, int height) {
  check_grid(g, width, height);
  int need = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int sx, sy;
      rect_source_q4(g, x, y, sx, sy);
      const int ix = sx >> 4, iy = sy >> 4, ay = sy & 15;
      if (ix < -1 || ix >= width) continue;  // every tap is outside the image columns
      // a tap row matters when it is inside the image and has a non-zero weight
      if (iy >= 0 && iy < height) need = std::max(need, std::abs(iy - y));
      if (ay != 0 && iy + 1 >= 0 && iy + 1 < height) need = std::max(need, std::abs(iy + 1 - y));
    }
  return need;
}

}  // namespace sm
