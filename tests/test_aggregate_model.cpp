// Unit tests of the support-weight aggregation model (docs/algorithm.md, section 5)
// against independent truth: hand-computed cases, OpenCV box filters, and the
// reciprocal as a rounded floating-point division.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>

#include <cmath>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "aggregate.hpp"

namespace {

sm::HwConfig config(int census, int sw, int disp, int shift) {
  sm::HwConfig hw;
  hw.census = census;
  hw.sw = sw;
  hw.disp = disp;
  hw.cost_shift = shift;
  return hw;
}

// One voxel (x, y, level d) of a cost volume and its value.
struct Voxel {
  int x, y, d, v;
};

// Sets the voxels of `vol`.
void set_voxels(sm::CostVolume& vol, std::initializer_list<Voxel> vs) {
  for (const Voxel& w : vs) vol.at(w.x, w.y, w.d) = static_cast<uint8_t>(w.v);
}

// Each voxel of `vol` holds its value.
void check_voxels(const sm::CostVolume& vol, std::initializer_list<Voxel> vs) {
  for (const Voxel& w : vs) {
    INFO("x " << w.x << " y " << w.y << " d " << w.d);
    CHECK(vol.at(w.x, w.y, w.d) == w.v);
  }
}

std::array<uint8_t, 32> all_codes(uint8_t c) {
  std::array<uint8_t, 32> t{};
  t.fill(c);
  return t;
}

// Smooth blocks beside noisy ones, so that many different weights occur.
sm::Image8 mixed_image(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  sm::Image8 im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      im.at(x, y) =
          ((x / 5 + y / 3) % 2) ? static_cast<uint8_t>(rng()) : static_cast<uint8_t>(60 + 3 * x + (rng() % 4));
  return im;
}

}  // namespace

TEST_CASE("RECIP known values", "[aggregate]") {
  CHECK(sm::sw_recip(0) == 0);
  CHECK(sm::sw_recip(1) == 4096);
  CHECK(sm::sw_recip(2) == 2048);
  CHECK(sm::sw_recip(3) == 1365);  // 1365.33
  CHECK(sm::sw_recip(6) == 683);   // 682.67 rounds up
  CHECK(sm::sw_recip(7) == 585);   // 585.14
  CHECK(sm::sw_recip(25) == 164);  // 163.84
  CHECK(sm::sw_recip(100) == 41);  // 40.96
  CHECK(sm::sw_recip(196) == 21);  // 20.90: largest index, SW = 7
  // Every entry is 4096 / s rounded to nearest (no ties occur for s > 1).
  for (uint32_t s = 1; s <= 196; ++s) CHECK(sm::sw_recip(s) == static_cast<uint32_t>(std::lround(4096.0 / s)));
}

TEST_CASE("weight codes", "[aggregate]") {
  std::array<uint8_t, 32> t{};
  t[0] = 3;   // |dI| 0..7    -> 4
  t[1] = 2;   // |dI| 8..15   -> 2
  t[2] = 1;   // |dI| 16..23  -> 1
  t[3] = 0;   // |dI| 24..31  -> 0
  t[30] = 2;  // |dI| 240..247
  t[31] = 1;  // |dI| 248..255
  CHECK(sm::sw_weight(t, 0) == 4);
  CHECK(sm::sw_weight(t, 7) == 4);
  CHECK(sm::sw_weight(t, 8) == 2);
  CHECK(sm::sw_weight(t, 23) == 1);
  CHECK(sm::sw_weight(t, 24) == 0);
  CHECK(sm::sw_weight(t, 247) == 2);
  CHECK(sm::sw_weight(t, 248) == 1);
  CHECK(sm::sw_weight(t, 255) == 1);
}

TEST_CASE("a constant cost volume stays constant", "[aggregate]") {
  struct Pt {
    int census, sw, shift;
  };
  // Points where C * |s * RECIP(s) - 4096| < 2048 for every reachable weight sum s and
  // cost C, so the normalisation is exact.
  for (const Pt& p : {Pt{15, 3, 2}, Pt{7, 5, 2}, Pt{7, 3, 0}, Pt{7, 7, 2}}) {
    const sm::HwConfig hw = config(p.census, p.sw, 12, p.shift);
    const int cb = hw.census_bits();
    const sm::Image8 left = mixed_image(23, 14, 5);
    sm::CostVolume raw(23, 14, hw.disp);
    for (int y = 0; y < raw.h; ++y)
      for (int x = 0; x < raw.w; ++x)
        for (int d = 0; d < hw.disp; ++d) raw.at(x, y, d) = static_cast<uint8_t>((d * 37) % (cb + 1));
    std::array<uint8_t, 32> t{};
    std::mt19937 rng(9);
    for (auto& c : t) c = static_cast<uint8_t>(rng() & 3);
    t[0] = 2;  // the centre always has a weight
    const sm::CostVolume out = sm::sw_aggregate(raw, left, t, hw);
    int bad = 0;
    for (int y = 0; y < raw.h; ++y)
      for (int x = 0; x < raw.w; ++x)
        for (int d = 0; d < hw.disp; ++d) bad += out.at(x, y, d) != (raw.at(x, y, d) >> p.shift);
    INFO("census " << p.census << " sw " << p.sw << " shift " << p.shift);
    CHECK(bad == 0);
  }
}

TEST_CASE("constant volume at the paper point: exact up to the stated rounding", "[aggregate]") {
  // SW = 5, CMAX = 56: a few (weight sum, cost) pairs round one up (e.g. s = 78, C = 54:
  // 78 * RECIP(78) = 4134); small costs are always exact.
  const sm::HwConfig hw = config(15, 5, 57, 0);
  sm::HwConfig hw2 = hw;
  hw2.cost_shift = 2;
  const sm::Image8 left = mixed_image(31, 17, 11);
  sm::CostVolume raw(31, 17, 57);
  for (int y = 0; y < raw.h; ++y)
    for (int x = 0; x < raw.w; ++x)
      for (int d = 0; d < 57; ++d) raw.at(x, y, d) = static_cast<uint8_t>(4 * d);
  std::array<uint8_t, 32> t{};
  t.fill(1);
  t[0] = 3;
  t[1] = 2;
  t[3] = 0;
  t[5] = 3;
  const sm::CostVolume out = sm::sw_aggregate(raw, left, t, hw2);
  int off = 0;
  for (int y = 0; y < raw.h; ++y)
    for (int x = 0; x < raw.w; ++x)
      for (int d = 0; d < 57; ++d) {
        const int c = d, o = out.at(x, y, d);
        if (c <= 20) REQUIRE(o == c);
        REQUIRE(std::abs(o - c) <= 1);
        off += o != c;
      }
  CHECK(off < raw.w * raw.h * 57 / 20);
}

TEST_CASE("all-equal codes give the box-filter mean", "[aggregate]") {
  for (int sw : {3, 5, 7}) {
    for (uint8_t code : {1, 2, 3}) {
      const sm::HwConfig hw = config(15, sw, 6, 2);
      const int w = 19, h = 13;
      std::mt19937 rng(static_cast<uint32_t>(sw * 10 + code));
      sm::Image8 left(w, h);
      for (auto& p : left.px) p = static_cast<uint8_t>(rng());  // codes all equal: irrelevant
      sm::CostVolume raw(w, h, hw.disp);
      for (auto& v : raw.v) v = static_cast<uint8_t>(rng() % 225);
      const sm::CostVolume out = sm::sw_aggregate(raw, left, all_codes(code), hw);

      // Window sums and in-image counts from OpenCV, zero outside the image.
      const cv::Mat ones(h, w, CV_32F, cv::Scalar(1.0f));
      cv::Mat count;
      cv::boxFilter(ones, count, CV_32F, cv::Size(sw, sw), cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
      int bad = 0;
      for (int d = 0; d < hw.disp; ++d) {
        cv::Mat c(h, w, CV_32F), sum;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) c.at<float>(y, x) = static_cast<float>(raw.at(x, y, d) >> 2);
        cv::boxFilter(c, sum, CV_32F, cv::Size(sw, sw), cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const long s = std::lround(sum.at<float>(y, x));
            const long n = std::lround(count.at<float>(y, x));
            const long wt = 1L << (code - 1);
            // The spec's rounding: sum * round(4096 / wsum) rounded at 2^12.
            const long recip = std::lround(4096.0 / static_cast<double>(wt * n));
            const long want = (wt * s * recip + 2048) >> 12;
            const double mean = static_cast<double>(s) / static_cast<double>(n);
            bad += out.at(x, y, d) != want;
            bad += std::abs(out.at(x, y, d) - mean) > 1.0;
          }
      }
      INFO("sw " << sw << " code " << int(code));
      CHECK(bad == 0);
    }
  }
}

TEST_CASE("weights are zero outside the image", "[aggregate]") {
  const sm::HwConfig hw = config(15, 3, 2, 0);
  sm::Image8 left(4, 3, 50);
  sm::CostVolume raw(4, 3, 2, 200);  // neighbours outside the corners' windows
  set_voxels(raw, {{0, 0, 0, 4}, {1, 0, 0, 8}, {0, 1, 0, 12}, {1, 1, 0, 16}});  // level 0
  set_voxels(raw, {{0, 0, 1, 1}, {1, 0, 1, 2}, {0, 1, 1, 2}, {1, 1, 1, 2}});    // level 1
  const sm::CostVolume out = sm::sw_aggregate(raw, left, all_codes(1), hw);
  // Corner (0,0): 4 in-image neighbours, (4+8+12+16)/4 = 10; (1+2+2+2)/4 = 1.75 -> 2.
  check_voxels(out, {{0, 0, 0, 10}, {0, 0, 1, 2}});
  // Corner (3,2): its 4 in-image neighbours all hold 200.
  // Edge (1,0): 6 in-image neighbours: (4+8+200+12+16+200)/6 = 73.33 -> 73.
  check_voxels(out, {{3, 2, 0, 200}, {1, 0, 0, 73}});
}

TEST_CASE("adaptive weights, hand-computed", "[aggregate]") {
  // 3x3 image around centre (1,1): all 100 except (2,1) = 200 (|dI| = 100, k = 12).
  const sm::HwConfig hw = config(15, 3, 2, 0);
  sm::Image8 left(3, 3, 100);
  left.at(2, 1) = 200;
  sm::CostVolume raw(3, 3, 2, 10);
  set_voxels(raw, {{2, 1, 0, 22}, {2, 1, 1, 0}});
  std::array<uint8_t, 32> t{};
  t[0] = 1;   // equal intensity: weight 1
  t[12] = 3;  // the bright neighbour: weight 4
  const sm::CostVolume out = sm::sw_aggregate(raw, left, t, hw);
  // wsum = 8 * 1 + 4 = 12, RECIP(12) = 341.
  // level 0: (8*10 + 4*22) = 168 -> (168*341 + 2048) >> 12 = 14
  // level 1: (8*10 + 4*0) = 80 -> (80*341 + 2048) >> 12 = 7 (6.66 rounds up)
  // Pixel (2,1) (value 200): its in-image neighbours (1,0),(1,1),(1,2),(2,0),(2,2) all
  // differ by 100 -> weight 4, itself weight 1: wsum 21, RECIP(21) = 195.
  // level 0: 5*4*10 + 22 = 222 -> (222*195 + 2048) >> 12 = 11 (222/21 = 10.57)
  check_voxels(out, {{1, 1, 0, 14}, {1, 1, 1, 7}, {2, 1, 0, 11}});
}

TEST_CASE("cost shift, zero weight sum and bad input", "[aggregate]") {
  const sm::HwConfig hw = config(7, 3, 4, 2);
  sm::Image8 left(5, 5, 9);
  sm::CostVolume raw(5, 5, 4, 47);  // 47 >> 2 = 11
  CHECK(sm::sw_aggregate(raw, left, all_codes(2), hw).at(2, 2, 3) == 11);
  // Every weight 0: wsum 0, RECIP(0) = 0, the output is 0.
  CHECK(sm::sw_aggregate(raw, left, all_codes(0), hw).at(2, 2, 0) == 0);
  CHECK_THROWS_AS(sm::sw_aggregate(raw, sm::Image8(4, 5), all_codes(1), hw), std::invalid_argument);
  CHECK_THROWS_AS(sm::sw_aggregate(sm::CostVolume(5, 5, 6), left, all_codes(1), hw), std::invalid_argument);
}

TEST_CASE("sw_aggregate equals the per-pixel sum at wide level counts and mixed weights", "[aggregate]") {
  // Written from the spec (docs/algorithm.md section 5) pixel by pixel: level counts that
  // take every block width of the vector kernels (32, 64, 128 levels and their tails).
  struct P {
    int sw, disp, shift;
  };
  for (const P p : {P{5, 128, 2}, P{7, 65, 0}, P{3, 200, 2}, P{5, 97, 1}}) {
    const sm::HwConfig hw = config(15, p.sw, p.disp, p.shift);
    const int w = 21, h = 9, r = (p.sw - 1) / 2;
    std::mt19937 rng(static_cast<uint32_t>(p.disp));
    sm::Image8 left(w, h);
    for (auto& v : left.px) v = static_cast<uint8_t>(rng() % 96);  // |dI| >> 3: 0..11
    std::array<uint8_t, 32> table{};
    for (size_t k = 0; k < table.size(); ++k) table[k] = static_cast<uint8_t>(rng() % 4);
    sm::CostVolume raw(w, h, hw.disp);
    for (auto& v : raw.v) v = static_cast<uint8_t>(rng() % 225);
    const sm::CostVolume out = sm::sw_aggregate(raw, left, table, hw);
    const uint32_t cmax = (1u << hw.cost_bits()) - 1;
    int bad = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int d = 0; d < hw.disp; ++d) {
          uint32_t sum = 0, wsum = 0;
          for (int j = -r; j <= r; ++j)
            for (int i = -r; i <= r; ++i) {
              if (x + i < 0 || x + i >= w || y + j < 0 || y + j >= h) continue;
              const uint32_t wt = sm::sw_weight(table, std::abs(left.at(x + i, y + j) - left.at(x, y)));
              wsum += wt;
              sum += wt * (raw.at(x + i, y + j, d) >> p.shift);
            }
          const uint32_t want = std::min((sum * sm::sw_recip(wsum) + 2048) >> 12, cmax);
          bad += out.at(x, y, d) != want;
        }
    INFO("sw " << p.sw << " levels " << p.disp << " shift " << p.shift);
    CHECK(bad == 0);
  }
}
