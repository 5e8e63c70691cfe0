// The speckle check of the output study (tools/sm_speckle.hpp): on the whole frame it must
// give OpenCV's filterSpeckles verdict (independent code), and in its streaming form a
// region is judged only on the rows seen K rows after its row.
#include <catch2/catch.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "sm_speckle.hpp"
#include "sm_speckle_table.hpp"

using namespace sm::tools;

namespace {

// Random disparities in a few levels, so regions of every size form, a quarter invalid.
cv::Mat random_map(int w, int h, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat m(h, w, CV_16S);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      m.at<int16_t>(y, x) = rng.uniform(0, 4) == 0 ? int16_t{-16} : static_cast<int16_t>(16 * rng.uniform(0, 3));
  return m;
}

// The pixels filterSpeckles keeps, in speckle_keep's form (invalid and removed: 0).
cv::Mat opencv_keep(const cv::Mat& q4, int max_size, int max_diff) {
  cv::Mat f = q4.clone();
  f.setTo(-16, q4 < 0);  // (filterSpeckles skips pixels equal to its new value)
  cv::filterSpeckles(f, -16, max_size, max_diff);
  cv::Mat keep = f != -16;
  return keep / 255;
}

}  // namespace

TEST_CASE("speckle check on the whole frame equals OpenCV's filterSpeckles", "[speckle]") {
  int mixed = 0;  // cases where some valid pixels are kept and some removed
  for (const auto& [w, h] : {std::pair{37, 23}, std::pair{64, 48}, std::pair{5, 81}})
    for (const int max_size : {1, 4, 30, 200})
      for (const int max_diff : {0, 16}) {
        const cv::Mat q4 = random_map(w, h, static_cast<uint64_t>(w * 1000 + max_size * 10 + max_diff));
        const cv::Mat ours = speckle_keep(q4, max_size, max_diff, h);
        CAPTURE(w, h, max_size, max_diff);
        REQUIRE(cv::countNonZero(ours != opencv_keep(q4, max_size, max_diff)) == 0);
        const int kept = cv::countNonZero(ours), valid = cv::countNonZero(q4 >= 0);
        mixed += kept > 0 && kept < valid;
      }
  CHECK(mixed >= 12);  // of 24
}

TEST_CASE("streaming speckle check: a region still reaching the newest row is kept", "[speckle]") {
  // A 3-pixel region in rows 1..2 (level 5), a large region of level 40 in column 0 from
  // row 0 to the last row; the rest invalid.
  cv::Mat q4(8, 6, CV_16S, cv::Scalar(-16));
  for (int y = 0; y < 8; ++y) q4.at<int16_t>(y, 0) = 40 * 16;
  q4.at<int16_t>(1, 3) = q4.at<int16_t>(1, 4) = q4.at<int16_t>(2, 3) = 5 * 16;
  auto small_kept = [&](int delay) { return speckle_keep(q4, 5, 8, delay).at<uint8_t>(1, 3) == 1; };
  CHECK(small_kept(0));   // row 1 judged when row 1 is the newest: open
  CHECK(small_kept(1));   // row 1 judged after row 2: the region reaches row 2, open
  CHECK(!small_kept(2));  // after row 3: closed at 3 pixels <= 5
  CHECK(!small_kept(8));  // the whole frame
  // Row 2 of the small region: judged after row 3 at delay 1, so closed.
  CHECK(speckle_keep(q4, 5, 8, 1).at<uint8_t>(2, 3) == 0);
  // The column region (8 pixels > 5) is kept at every delay once it is complete, and while
  // it reaches the newest row.
  for (const int delay : {0, 1, 2, 3, 8}) {
    const cv::Mat keep = speckle_keep(q4, 5, 8, delay);
    for (int y = 0; y < 8; ++y) CHECK(keep.at<uint8_t>(y, 0) == 1);
    CHECK(keep.at<uint8_t>(0, 1) == 0);  // invalid stays 0
  }
  // Made small (max_size 8): the column is a speckle once the whole frame is seen, so the
  // rows decided at the frame's end (the last `delay` + 1) lose it, earlier rows keep it.
  const cv::Mat k2 = speckle_keep(q4, 8, 8, 2);
  for (int y = 0; y < 5; ++y) CHECK(k2.at<uint8_t>(y, 0) == 1);
  for (int y = 5; y < 8; ++y) CHECK(k2.at<uint8_t>(y, 0) == 0);
}

TEST_CASE("streaming speckle check: what it holds at once", "[speckle]") {
  // A U (two arms at level 0 joined on row 1) and, below it, a separate pixel at level 10:
  //   row 0:  0 . 0 . .
  //   row 1:  0 0 0 . .
  //   row 2:  . . . . 10
  cv::Mat q4(3, 5, CV_16S, cv::Scalar(-16));
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{2, 0}, std::pair{0, 1}, std::pair{1, 1}, std::pair{2, 1}})
    q4.at<int16_t>(y, x) = 0;
  q4.at<int16_t>(2, 4) = 160;
  // All rows pending: two regions at most (the arms, then the U and the pixel), but three
  // labels once the pixel comes (the arms keep the labels they were given before the join).
  const SpeckleHold all = speckle_hold(q4, 8, 10);
  CHECK(all.regions == 2);
  CHECK(all.labels == 3);
  // Only the newest row pending: the arms on row 0; row 1 is labelled after its join.
  const SpeckleHold newest = speckle_hold(q4, 8, 0);
  CHECK(newest.regions == 2);
  CHECK(newest.labels == 2);
  // Level 10 within the difference: the pixel is still separate (no 4-neighbour), the same.
  CHECK(speckle_hold(q4, 160, 10).labels == 3);
}

TEST_CASE("speckle check with a label table: the ideal verdict or more kept", "[speckle]") {
  int tested = 0;
  for (const auto& [w, h] : {std::pair{37, 23}, std::pair{64, 48}, std::pair{5, 81}})
    for (const int max_size : {1, 4, 30})
      for (const int max_diff : {0, 16}) {
        const cv::Mat q4 = random_map(w, h, static_cast<uint64_t>(w * 7919 + max_size * 31 + max_diff));
        INFO(w << "x" << h << " S " << max_size << " D " << max_diff);
        // The whole frame with labels to spare: exactly the ideal (filterSpeckles') verdict.
        sm::SpeckleStats st;
        const cv::Mat whole = speckle_keep_table(q4, max_size, max_diff, h, w * h, &st);
        CHECK(cv::countNonZero(whole != speckle_keep(q4, max_size, max_diff, h)) == 0);
        CHECK(st.keep_pixels == 0);
        // Streaming, any table: every pixel the ideal streaming check keeps is kept.
        for (const int delay : {1, 3})
          for (const int labels : {w * h, 16, 2}) {
            const cv::Mat ideal = speckle_keep(q4, max_size, max_diff, delay);
            const cv::Mat table = speckle_keep_table(q4, max_size, max_diff, delay, labels);
            CHECK(cv::countNonZero(ideal & ~table) == 0);
            ++tested;
          }
      }
  CHECK(tested == 108);
}

TEST_CASE("speckle check with a label table: labels come back once their pixels are decided", "[speckle]") {
  // A single valid pixel on every other row of column 1: each its own region of one pixel.
  cv::Mat q4(40, 3, CV_16S, cv::Scalar(-16));
  for (int y = 0; y < 40; y += 2) q4.at<int16_t>(y, 1) = 80;
  sm::SpeckleStats st;
  // Decided 2 rows later: at most two labels are held at once, so two suffice for 20 regions.
  const cv::Mat keep = speckle_keep_table(q4, 1, 0, 2, 2, &st);
  CHECK(st.keep_pixels == 0);
  CHECK(st.peak_labels == 2);
  CHECK(cv::countNonZero(keep) == 0);  // every one a speckle of 1 pixel
  // One label: the second region finds the table full and is kept.
  const cv::Mat one = speckle_keep_table(q4, 1, 0, 2, 1, &st);
  CHECK(st.keep_pixels > 0);
  CHECK(cv::countNonZero(one) == st.keep_pixels);
}

// A region of at most SPECKLE_SIZE pixels is still kept when it holds more than
// SPECKLE_TRUST pixels and fewer than 1/16 of them fail the left-right check (confidence
// bit 7 clear). Three 12 x 12 squares (144 pixels) at levels of their own on invalid
// ground, with 0, 8 and 9 pixels failing: 8 x 16 < 144 is trusted, 9 x 16 = 144 is not.
TEST_CASE("speckle stage: a region both views agree on is trusted", "[speckle]") {
  sm::OutImage in(60, 20);
  const int fails[] = {0, 8, 9};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 144; ++i) {
      const int x = 4 + 20 * k + i % 12, y = 4 + i / 12;
      const unsigned conf = i < fails[k] ? 0x7f : 0x80;
      in.at(x, y) = sm::make_out_word(true, conf, static_cast<unsigned>(160 * (k + 1)));
    }
  auto kept = [&](uint16_t trust, int rows) {
    sm::SpeckleRegs regs;
    regs.en = 1;
    regs.size = 1000;
    regs.diff = 8;
    regs.trust = trust;
    sm::SpeckleStats st;
    const sm::OutImage out = sm::speckle_output(in, regs, rows, 64, &st);
    std::vector<int> n(3, 0);
    for (int k = 0; k < 3; ++k) n[static_cast<size_t>(k)] = sm::out_valid(out.at(4 + 20 * k, 4));
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 144; ++i)  // a region's pixels share its verdict
        CHECK(sm::out_valid(out.at(4 + 20 * k + i % 12, 4 + i / 12)) == (n[static_cast<size_t>(k)] != 0));
    CHECK(st.trusted == 144 * (n[0] + n[1]));
    return n;
  };
  for (const int rows : {14, 32}) {  // (decided after the squares' last row)
    CAPTURE(rows);
    CHECK(kept(100, rows) == std::vector<int>{1, 1, 0});
    CHECK(kept(143, rows) == std::vector<int>{1, 1, 0});
    CHECK(kept(144, rows) == std::vector<int>{0, 0, 0});  // more than SPECKLE_TRUST pixels
    CHECK(kept(4095, rows) == std::vector<int>{0, 0, 0});
  }
}
