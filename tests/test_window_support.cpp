// Unit tests of the window supports of sm_output_study --study window-conf
// (tools/sm_window_support.hpp): known answers on hand-made words, the offsets' shapes,
// and a brute-force count on random words.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <random>
#include <vector>

#include "sm_window_support.hpp"

namespace {

using sm::OutImage;
using sm::tools::Offset;

// Words of a w x h frame from Q.4 values, negative = invalid.
OutImage words_of(int w, int h, const std::vector<int>& q4) {
  OutImage o(w, h);
  for (size_t i = 0; i < q4.size(); ++i)
    o.px[i] = q4[i] < 0 ? 0u : sm::make_out_word(true, 0, static_cast<unsigned>(q4[i]));
  return o;
}

}  // namespace

TEST_CASE("offset shapes: the row's samples and the ring at r", "[unit][tools]") {
  const std::vector<Offset> row = sm::tools::row_offsets(15, 3);
  CHECK(row.size() == 10);
  CHECK(row.front().dx == -3);
  CHECK(row.back().dx == 15);
  const std::vector<Offset> ring = sm::tools::ring_offsets(10, false), above = sm::tools::ring_offsets(10, true);
  CHECK(ring.size() == 8);
  CHECK(above.size() == 5);
  for (const Offset& o : ring) CHECK((o.dy || o.dx));
  for (const Offset& o : above) CHECK(o.dy <= 0);
}

TEST_CASE("offset_support: known answers (tolerance, invalid words, frame border)", "[unit][tools]") {
  // one row: 100 100 120 -1 130, tolerance 16 (one pixel in Q.4)
  const OutImage w = words_of(5, 1, {100, 100, 120, -1, 130});
  const std::vector<uint16_t> n = sm::tools::offset_support(w, sm::tools::row_offsets(2, 1), 16);
  CHECK(n == std::vector<uint16_t>{1, 1, 1, 0, 1});
  // each 100 sees the other 100 only (120 is 20 away), 120 sees 130 only (the word at +1 is
  // invalid), the invalid word counts nothing, 130 sees 120 (-2) only; at 20, 120 joins the
  // 100s
  const std::vector<uint16_t> t20 = sm::tools::offset_support(w, sm::tools::row_offsets(2, 1), 20);
  CHECK(t20 == std::vector<uint16_t>{2, 2, 3, 0, 1});
  // the ring at 1 around the centre of a 3x3 frame, and its rows above only
  const OutImage g = words_of(3, 3, {50, 60, 70, 50, 50, 90, 40, 50, 50});
  CHECK(sm::tools::offset_support(g, sm::tools::ring_offsets(1, false), 10)[4] == 6);  // 60, 50 x4, 40
  CHECK(sm::tools::offset_support(g, sm::tools::ring_offsets(1, true), 10)[4] == 3);   // 50, 60, 50
}

TEST_CASE("offset_support: random words against a direct count", "[unit][tools]") {
  std::mt19937 rng(7);
  const int w = 23, h = 17;
  std::vector<int> q(static_cast<size_t>(w * h));
  for (int& v : q) v = rng() % 5 == 0 ? -1 : static_cast<int>(rng() % 64);
  const OutImage o = words_of(w, h, q);
  const std::vector<Offset> offs = sm::tools::ring_offsets(3, false);
  const std::vector<uint16_t> n = sm::tools::offset_support(o, offs, 8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int k = 0;
      const int c = q[static_cast<size_t>(y * w + x)];
      for (const Offset& f : offs) {
        const int yy = y + f.dy, xx = x + f.dx;
        if (c < 0 || yy < 0 || yy >= h || xx < 0 || xx >= w) continue;
        const int v = q[static_cast<size_t>(yy * w + xx)];
        k += v >= 0 && std::abs(v - c) <= 8;
      }
      REQUIRE(n[static_cast<size_t>(y * w + x)] == k);
    }
}
