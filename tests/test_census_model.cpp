// Model unit tests of census_transform, hamming_cost and matching_cost against independent truth:
// hand-computed vectors and costs, a naive per-bit reference, brightness invariance
// and the known disparity of a shifted random texture.
#include <algorithm>
#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <random>
#include <tuple>

#include "census.hpp"

namespace {

sm::HwConfig config(int census, int disp = 16) {
  sm::HwConfig hw;
  hw.census = census;
  hw.disp = disp;
  return hw;
}

sm::Image8 random_image(int w, int h, uint32_t seed, int max_v = 255) {
  std::mt19937 rng(seed);
  sm::Image8 im(w, h);
  for (auto& p : im.px) p = static_cast<uint8_t>(rng() % (max_v + 1));
  return im;
}

// Straight from the spec text, one bit at a time.
sm::CensusVec naive_census(const sm::Image8& im, int x, int y, int census) {
  const int r = (census - 1) / 2;
  sm::CensusVec v{0, 0, 0, 0};
  int k = 0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const int nx = std::clamp(x + dx, 0, im.w - 1), ny = std::clamp(y + dy, 0, im.h - 1);
      if (im.at(nx, ny) < im.at(x, y)) v[k / 64] |= uint64_t{1} << (k % 64);
      ++k;
    }
  return v;
}

}  // namespace

TEST_CASE("census of a hand-made 5x5 patch", "[census]") {
  sm::Image8 im(5, 5);
  const uint8_t px[25] = {10,  20,  30, 40, 50, 60, 70,  80, 90, 100, 110, 120, 50,
                          130, 140, 0,  5,  50, 45, 255, 49, 51, 50,  1,   2};
  for (int i = 0; i < 25; ++i) im.px[i] = px[i];
  const auto c = sm::census_transform(im, config(5));
  // centre 50: smaller are 10 20 30 40 (k 0-3), 0 5 (k 14, 15), 45 (k 17), 49 (k 19),
  // 1 2 (k 22, 23); equal neighbours (50) give 0
  CHECK(c.at(2, 2) == sm::CensusVec{0xCAC00Full, 0, 0, 0});
  // corner (4, 4) = 2: the 1 at (3, 4) is the only smaller pixel; an outside neighbour
  // is the nearest inside pixel, so rows dy = 1, 2 repeat row 4: k 11 (dx -1, dy 0), then
  // k 15 and k 20 (dx -1, dy 1 and 2); columns dx = 1, 2 repeat the centre (bit 0)
  CHECK(c.at(4, 4) == sm::CensusVec{0x108800ull, 0, 0, 0});
  // corner (0, 0) = 10: every neighbour, inside or clamped, is larger or the centre
  CHECK(c.at(0, 0) == sm::CensusVec{0, 0, 0, 0});
  // (0, 2) = 110: columns dx = -2, -1 repeat column 0, so each row reads columns
  // 0, 0, 0, 1, 2: rows 0, 1, 3, 4 are all smaller (10 10 10 20 30, 60 60 60 70 80,
  // 0 0 0 5 50, 49 49 49 51 50); in the centre row (110 110 c 120 50) only the 50
  CHECK(c.at(0, 2) == sm::CensusVec{0xFFFFFFull & ~(0x7ull << 10), 0, 0, 0});
}

TEST_CASE("census matches the per-bit definition for every window size", "[census]") {
  for (int census = 3; census <= 15; census += 2) {
    const auto im = random_image(23, 19, 100 + census, census % 3 ? 255 : 7);
    const auto c = sm::census_transform(im, config(census));
    for (int y = 0; y < im.h; ++y)
      for (int x = 0; x < im.w; ++x) {
        INFO("census " << census << " x " << x << " y " << y);
        REQUIRE(c.at(x, y) == naive_census(im, x, y, census));
      }
  }
}

TEST_CASE("census is invariant under a monotonic brightness change", "[census]") {
  const auto im = random_image(40, 30, 5, 126);
  sm::Image8 bright = im;
  for (auto& p : bright.px) p = static_cast<uint8_t>(2 * p + 3);  // <= 255, no saturation
  for (int census : {7, 15}) {
    const auto hw = config(census);
    CHECK(sm::census_transform(im, hw) == sm::census_transform(bright, hw));
  }
  // saturation is not monotonic-strict: the vectors must change somewhere
  sm::Image8 flat = im;
  for (auto& p : flat.px) p = static_cast<uint8_t>(p > 60 ? 60 : p);
  CHECK_FALSE(sm::census_transform(im, config(7)) == sm::census_transform(flat, config(7)));
}

TEST_CASE("Hamming cost known answers and the x - d < 0 rule", "[cost]") {
  const auto hw = config(5, 4);  // CB = 24
  sm::CensusImage cl(4, 1, sm::CensusVec{0, 0, 0, 0}), cr(4, 1, sm::CensusVec{0, 0, 0, 0});
  cl.at(0, 0) = {0x3, 0, 0, 0};
  cl.at(3, 0) = {0xFF, 0, 0, 0};
  cr.at(0, 0) = {0x1, 0, 0, 0};
  cr.at(1, 0) = {0xF0F, 0, 0, 0};
  cr.at(2, 0) = {0x1, 0, 0, 0};
  cr.at(3, 0) = {0xFF, 0, 0, 0};
  const auto h = sm::hamming_cost(cl, cr, hw);
  REQUIRE(h.d == 4);
  CHECK(h.at(3, 0, 0) == 0);                               // 0xFF ^ 0xFF
  CHECK(h.at(3, 0, 1) == 7);                               // 0xFF ^ 0x1 = 0xFE
  CHECK(h.at(3, 0, 2) == 8);                               // 0xFF ^ 0xF0F = 0xFF0
  CHECK(h.at(3, 0, 3) == 7);                               // x - d = 0: 0xFF ^ 0x1
  CHECK(h.at(0, 0, 0) == 1);                               // 0x3 ^ 0x1
  for (int d = 1; d < 4; ++d) CHECK(h.at(0, 0, d) == 24);  // x - d < 0
  CHECK(h.at(1, 0, 2) == 24);
  CHECK(h.at(2, 0, 3) == 24);

  // bits in the upper words count too (15x15: 224 bits)
  const auto hw15 = config(15, 4);
  sm::CensusImage a(1, 1, sm::CensusVec{0, 0, 0, 0}), b(1, 1, sm::CensusVec{0, 0, 0, 0});
  a.at(0, 0) = {0, 0x5, 0, uint64_t{1} << 31};  // bits 64, 66, 223
  const auto h15 = sm::hamming_cost(a, b, hw15);
  CHECK(h15.at(0, 0, 0) == 3);
  CHECK(h15.at(0, 0, 1) == 224);

  CHECK_THROWS_AS(sm::hamming_cost(cl, a, hw), std::invalid_argument);
}

TEST_CASE("Hamming cost equals its definition on random 256-bit vectors", "[cost]") {
  // Every bit of the four words set at random (also above CB), an all-ones left pixel
  // against all-zero right pixels (popcount 256: 0 as an 8-bit H), widths and level
  // counts that exercise the 8-level blocks of the vector kernels and their tails.
  std::mt19937_64 rng(5);
  for (const auto& [w, disp] : {std::pair{70, 128}, std::pair{37, 37}, std::pair{9, 16}, std::pair{130, 254}}) {
    INFO("width " << w << " levels " << disp);
    const auto hw = config(15, disp);  // CB = 224
    sm::CensusImage cl(w, 2, sm::CensusVec{0, 0, 0, 0}), cr(w, 2, sm::CensusVec{0, 0, 0, 0});
    for (auto& v : cl.px) v = {rng(), rng(), rng(), rng()};
    for (auto& v : cr.px) v = {rng(), rng(), rng(), rng()};
    cl.at(w - 1, 1) = {~0ull, ~0ull, ~0ull, ~0ull};
    for (int x = 0; x < w; ++x) cr.at(x, 1) = {0, 0, 0, 0};
    const auto h = sm::hamming_cost(cl, cr, hw);
    int wrong = 0;
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < w; ++x)
        for (int d = 0; d < disp; ++d) {
          int want = 224;
          if (x >= d) {
            want = 0;
            for (size_t i = 0; i < 4; ++i) want += __builtin_popcountll(cl.at(x, y)[i] ^ cr.at(x - d, y)[i]);
            want &= 0xff;
          }
          wrong += h.at(x, y, d) != want;
        }
    CHECK(wrong == 0);
    CHECK(h.at(w - 1, 1, 0) == 0);  // 256 as an 8-bit H
  }
}

TEST_CASE("minimum cost finds the shift of a random texture", "[cost]") {
  const int w = 80, h = 24, shift = 9;
  const auto hw = config(7, 16);
  const int r = 3;
  const auto left = random_image(w, h, 77);
  sm::Image8 right(w, h);
  std::mt19937 rng(78);
  // the left pixel x is the right pixel x - shift
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) right.at(x, y) = x + shift < w ? left.at(x + shift, y) : static_cast<uint8_t>(rng());
  const auto cost = sm::hamming_cost(sm::census_transform(left, hw), sm::census_transform(right, hw), hw);
  // The true level costs 0 everywhere its windows are identical; another level can tie
  // only by chance (a locally extreme centre gives an all-ones vector at any level), so
  // the true level must be the unique minimum almost everywhere.
  int checked = 0, unique = 0;
  for (int y = 0; y < h; ++y)
    for (int x = shift + r; x + r < w - shift; ++x) {
      INFO("x " << x << " y " << y);
      REQUIRE(cost.at(x, y, shift) == 0);
      int at_min = 0;
      for (int d = 0; d < hw.disp; ++d) at_min += cost.at(x, y, d) == 0;
      unique += at_min == 1;
      ++checked;
    }
  CHECK(unique >= checked * 97 / 100);
  CHECK(checked > 500);
}

TEST_CASE("census border equals a census of the replicate-padded image (OpenCV)", "[census]") {
  // Independent truth for the border rule: cv::copyMakeBorder(BORDER_REPLICATE) pads the
  // image, and the plain census of the padded image's inside pixels has no border at all.
  for (int census : {3, 7, 15}) {
    const int r = (census - 1) / 2;
    const auto im = random_image(21, 17, 300 + census, census == 7 ? 9 : 255);
    cv::Mat m(im.h, im.w, CV_8U, const_cast<uint8_t*>(im.px.data())), pad;
    cv::copyMakeBorder(m, pad, r, r, r, r, cv::BORDER_REPLICATE);
    const auto c = sm::census_transform(im, config(census));
    for (int y = 0; y < im.h; ++y)
      for (int x = 0; x < im.w; ++x) {
        sm::CensusVec v{0, 0, 0, 0};
        int k = 0;
        for (int dy = -r; dy <= r; ++dy)
          for (int dx = -r; dx <= r; ++dx) {
            if (dx == 0 && dy == 0) continue;
            if (pad.at<uint8_t>(y + r + dy, x + r + dx) < pad.at<uint8_t>(y + r, x + r))
              v[static_cast<size_t>(k / 64)] |= uint64_t{1} << (k % 64);
            ++k;
          }
        INFO("census " << census << " x " << x << " y " << y);
        REQUIRE(c.at(x, y) == v);
      }
  }
}

TEST_CASE("matching cost adds the intensity term at the aggregation's scale, capped at CB", "[cost]") {
  // Flat images: every census vector is 0, so H = 0 and the cost is the term alone, by hand:
  // |100 - 120| = 20, >> 2 = 5, << COST_SHIFT 2 = 20; |100 - 40| = 60 >> 2 = 15, capped at 7: 28.
  const int w = 12, h = 3;
  auto hw = config(5, 8);  // CB = 24
  sm::Image8 left(w, h), r120(w, h), r40(w, h);
  std::fill(left.px.begin(), left.px.end(), uint8_t{100});
  std::fill(r120.px.begin(), r120.px.end(), uint8_t{120});
  std::fill(r40.px.begin(), r40.px.end(), uint8_t{40});
  const auto cl = sm::census_transform(left, hw);
  const auto c120 = sm::matching_cost(cl, sm::census_transform(r120, hw), left, r120, hw);
  const auto c40 = sm::matching_cost(cl, sm::census_transform(r40, hw), left, r40, hw);
  CHECK(c120.at(5, 1, 3) == 20);
  CHECK(c40.at(5, 1, 3) == 24);   // 28 capped at CB
  CHECK(c120.at(2, 1, 3) == 24);  // x - d < 0: CB
  hw.ad_max = 0;                  // census only
  CHECK(sm::matching_cost(cl, sm::census_transform(r120, hw), left, r120, hw).at(5, 1, 3) == 0);
  hw.ad_max = 7;
  hw.ad_shift = 0;
  hw.cost_shift = 1;  // min(20, 7) << 1
  CHECK(sm::matching_cost(cl, sm::census_transform(r120, hw), left, r120, hw).at(5, 1, 3) == 14);
  // On random pairs: H plus the term, capped, level by level (the naive sum); 16 levels (the
  // vector kernels' tails only) and 128 (their 32-level blocks too), two shift pairs.
  for (const auto& [disp, ad_shift, cost_shift] :
       {std::tuple{16, 2, 2}, std::tuple{128, 2, 2}, std::tuple{128, 0, 4}}) {
    INFO("levels " << disp << " AD_SHIFT " << ad_shift << " COST_SHIFT " << cost_shift);
    const int w = 160;
    const auto a = random_image(w, 4, 91), b = random_image(w, 4, 92);
    hw = config(15, disp);
    hw.ad_shift = ad_shift;
    hw.cost_shift = cost_shift;
    const auto ca = sm::census_transform(a, hw), cb = sm::census_transform(b, hw);
    const auto hm = sm::hamming_cost(ca, cb, hw), m = sm::matching_cost(ca, cb, a, b, hw);
    int wrong = 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < w; ++x)
        for (int d = 0; d < disp; ++d) {
          const int t = x >= d ? std::min(std::abs(a.at(x, y) - b.at(x - d, y)) >> ad_shift, 7) : 0;
          wrong += m.at(x, y, d) != std::min(hm.at(x, y, d) + (t << cost_shift), 224);
        }
    CHECK(wrong == 0);
    CHECK_THROWS_AS(sm::matching_cost(ca, cb, a, random_image(w - 1, 4, 93), hw), std::invalid_argument);
  }
}
