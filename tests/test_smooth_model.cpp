// The output words' window stage (model/smooth.hpp, docs/algorithm.md 9.7) against
// independent truth: the rounding against double arithmetic for every sum and count a
// window can give, known answers on small word images (planes, depth steps, invalid pixels,
// frame borders) for the mean and the confidence, and a noisy plane whose error the mean
// must lower; the row support of the confidence on hand-made rows.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "row_support.hpp"
#include "smooth.hpp"
#include "validity.hpp"

using namespace sm;

namespace {
OutImage words_of(int w, int h, unsigned (*q)(int, int)) {
  OutImage m(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at(x, y) = make_out_word(true, static_cast<unsigned>(x + 7 * y) & 0xff, q(x, y));
  return m;
}
// The Q.4 values of the words (invalid: -1), the confidence aside.
std::vector<int> q4s(const OutImage& m) {
  std::vector<int> v;
  for (const uint32_t w : m.px) v.push_back(out_valid(w) ? static_cast<int>(out_q4(w)) : -1);
  return v;
}
}  // namespace

TEST_CASE("smooth_offset is the mean rounded half up for every window sum and count", "[unit][smooth]") {
  CHECK(smooth_offset(0, 1) == 0);
  CHECK(smooth_offset(1, 2) == 1);    // +0.5 rounds up
  CHECK(smooth_offset(-1, 2) == 0);   // -0.5 rounds up too
  CHECK(smooth_offset(-3, 2) == -1);  // -1.5
  CHECK(smooth_offset(5, 3) == 2);    // 1.67
  CHECK(smooth_offset(-5, 3) == -2);  // -1.67
  long bad = 0;
  for (int k = 1; k <= 25; ++k)
    for (int s = -63 * (k - 1); s <= 63 * (k - 1); ++s)
      bad += smooth_offset(s, k) != static_cast<int>(std::floor(static_cast<double>(s) / k + 0.5));
  CHECK(bad == 0);
}

TEST_CASE("smoothing keeps planes of one value, depth steps and invalid pixels", "[unit][smooth]") {
  const OutImage flat = words_of(9, 7, [](int, int) { return 16u * 40 + 5; });
  CHECK(q4s(smooth_output(flat, 1, 24)) == q4s(flat));
  // two surfaces 2 px apart (32 > 24 in 1/16 px): neither takes the other's values
  const OutImage step = words_of(9, 7, [](int x, int) { return x < 4 ? 16u * 40 : 16u * 42; });
  CHECK(q4s(smooth_output(step, 1, 24)) == q4s(step));
  // an invalid word stays as it is (its failed rules too) and is left out of its
  // neighbours' means
  OutImage holes = words_of(9, 7, [](int, int) { return 16u * 40; });
  holes.at(4, 3) = make_out_word(false, 0xff, 16u * 40, kFailLr | kFailBorder);
  REQUIRE(holes.at(4, 3) == 0x22000000u);
  holes.at(2, 2) = make_out_word(true, 9, 16u * 41);  // within 24 of its neighbours
  const OutImage o = smooth_output(holes, 1, 24);
  CHECK(o.at(4, 3) == 0x22000000u);
  CHECK(out_fails(o.at(4, 3)) == (kFailLr | kFailBorder));
  // (2, 2): 24 neighbours at 640 (one invalid: 23) and itself at 656: 656 + floor(-368/24 + 1/2)
  CHECK(static_cast<int>(out_q4(o.at(2, 2))) == 656 + static_cast<int>(std::floor(-16.0 * 23 / 24 + 0.5)));
  // (0, 0): its window inside the frame is 3 x 3, (2, 2) among it: 640 + round(16 / 9)
  CHECK(out_q4(o.at(0, 0)) == 640u + 2u);
  CHECK(q4s(smooth_output(holes, 0, 24)) == q4s(holes));  // SMOOTH_EN 0
  CHECK(q4s(smooth_output(holes, 1, 0)) == q4s(holes));   // SMOOTH_T 0: equal values only
}

TEST_CASE("the stream's confidence adds the window's support to the evidence byte", "[unit][smooth]") {
  CHECK(support_confidence(0xff, 25, 25) == 204);  // every cue and the whole window agree
  CHECK(support_confidence(0x00, 1, 1) == 5);      // nothing but the pixel itself
  CHECK(support_confidence(0xa3, 10, 4) == 16 + 16 + 3 + 30 + 8);
  // a plane of one value: the whole window within 1/2 px (K = K_near = 25 inside, 9 at a
  // corner); the evidence byte of words_of is (x + 7 y) & 0xff
  const OutImage flat = words_of(9, 7, [](int, int) { return 16u * 40; });
  const OutImage o = smooth_output(flat, 1, 24);
  CHECK(out_conf(o.at(4, 3)) == 25u + 3 * 25 + 2 * 25);  // e = 25: ratio 25, no flag
  CHECK(out_conf(o.at(0, 0)) == 0u + 3 * 9 + 2 * 9);
  // one pixel a pixel above the rest: 24 of its window within SMOOTH_T, none within 1/2 px
  OutImage bump = flat;
  bump.at(4, 3) = make_out_word(true, 0x80, 16u * 41);
  const OutImage b = smooth_output(bump, 1, 24);
  CHECK(out_conf(b.at(4, 3)) == 16u + 3 * 25 + 2 * 1);
  CHECK(out_conf(smooth_output(bump, 1, 12).at(4, 3)) == 16u + 3 * 1 + 2 * 1);  // K follows SMOOTH_T
  // the confidence does not depend on SMOOTH_EN
  CHECK(out_conf(smooth_output(bump, 0, 24).at(4, 3)) == out_conf(b.at(4, 3)));
}

TEST_CASE("smoothing lowers the error of a noisy slanted plane, for any thread count", "[unit][smooth]") {
  std::mt19937 rng(7);
  const int w = 41, h = 23;
  OutImage m(w, h);
  auto truth = [](int x, int y) { return 16.0 * 30 + 0.75 * x + 0.5 * y; };  // in 1/16 px
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int noise = static_cast<int>(rng() % 17) - 8;
      m.at(x, y) = make_out_word(true, 0, static_cast<unsigned>(std::lround(truth(x, y)) + noise));
    }
  const OutImage o = smooth_output(m, 1, 24);
  double before = 0, after = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      before += std::abs(out_q4(m.at(x, y)) - truth(x, y));
      after += std::abs(out_q4(o.at(x, y)) - truth(x, y));
    }
  CHECK(after < 0.5 * before);
  CHECK(smooth_output(m, 1, 24, 3).px == o.px);
}

TEST_CASE("row support: known answers (samples, tolerance, row ends, invalid words, saturation)", "[unit][smooth]") {
  // rows of 40: a surface at 160 (level 10) with an island at 400 from x 14 to 20
  OutImage m(40, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 40; ++x) m.at(x, y) = make_out_word(true, 100, x >= 14 && x <= 20 ? 400u : 160u);
  CHECK(row_support(m, 0, 0) == 4);             // +3, +6, +9, +12 on the surface; +15 on the island
  CHECK(row_support(m, 17, 0) == 2);            // the island's centre: +-3 only
  CHECK(row_support(m, 30, 0) == 6);            // -15 and -12 on the island; -9 .. +9; +12, +15 outside
  CHECK(row_support(m, 39, 0) == 5);            // -3 .. -15 on the surface, the rest outside the row
  m.at(33, 0) = make_out_word(true, 100, 176);  // 16 away: still within one pixel
  m.at(36, 0) = make_out_word(true, 100, 177);  // 17 away: not
  CHECK(row_support(m, 39, 0) == 4);
  m.at(27, 1) = make_out_word(false, 0, 0, 1);  // an invalid sample counts nothing
  CHECK(row_support(m, 30, 1) == 5);
  m.at(5, 1) = make_out_word(true, 250, 160);  // 250 + 5 R (R 3) saturates
  const OutImage o = row_support_output(m);
  CHECK(out_conf(o.at(30, 1)) == 100u + 5 * 5);
  CHECK(o.at(27, 1) == m.at(27, 1));  // invalid words pass as they are
  CHECK(out_conf(o.at(5, 1)) == 255u);
  CHECK(out_q4(o.at(5, 1)) == 160u);  // the value passes
  // the stream: the smoothing, then the row support
  CHECK(smooth_stream(m, 1, 24).px == row_support_output(smooth_output(m, 1, 24)).px);
  CHECK(row_support_output(m, 3).px == o.px);  // any thread count
}
