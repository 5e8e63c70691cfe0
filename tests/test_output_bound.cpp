// The output-stage bound study (tools/sm_output_bound.hpp): its windowed features on small
// frames with known answers, and a leave-one-scene-out forest that must find the rule its
// training frames share.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "sm_output_bound.hpp"

using namespace sm;
using namespace sm::tools;

namespace {

// A w x h frame at level `level` everywhere, every pixel matched, a flat left image and
// ground truth equal to the level.
OutputFrame flat_frame(int w, int h, int level) {
  OutputFrame f;
  f.name = "flat";
  f.levels = 32;
  f.ev = Evidence(w, h);
  f.post = DispImage(w, h, make_disp(static_cast<unsigned>(level), true));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      f.ev.d.at(x, y) = static_cast<uint8_t>(level);
      f.ev.dw.at(x, y) = static_cast<uint8_t>(level);
      f.ev.lr.at(x, y) = static_cast<uint8_t>(level);
      f.ev.matched.at(x, y) = 1;
    }
  f.left = cv::Mat(h, w, CV_8UC1, cv::Scalar(100));
  f.gt = cv::Mat(h, w, CV_32F, cv::Scalar(level));
  return f;
}

int column(const std::string& name) {
  const auto& n = bound_feature_names();
  for (size_t k = 0; k < n.size(); ++k)
    if (n[k] == name) return static_cast<int>(k);
  FAIL("no feature " << name);
  return -1;
}

float feature(const cv::Mat& m, int w, int x, int y, const std::string& name) {
  return m.at<float>(y * w + x, column(name));
}

}  // namespace

TEST_CASE("bound features: level support, row distance to unmatched, texture") {
  const int w = 9, h = 5;
  OutputFrame f = flat_frame(w, h, 10);
  f.post.at(4, 2) = make_disp(20, true);  // one outlier level
  f.ev.matched.at(6, 3) = 0;              // one unmatched pixel
  for (int y = 0; y < h; ++y)
    for (int x = 5; x < w; ++x) f.left.at<uint8_t>(y, x) = 200;  // a vertical step edge at x 4|5
  const cv::Mat m = pixel_features(f);
  REQUIRE(m.rows == w * h);
  REQUIRE(m.cols == static_cast<int>(bound_feature_names().size()));
  CHECK(feature(m, w, 0, 0, "support 3x3") == 4);  // corner: 2 x 2 inside the frame
  CHECK(feature(m, w, 4, 2, "support 3x3") == 1);  // the outlier agrees only with itself
  CHECK(feature(m, w, 3, 2, "support 3x3") == 8);  // its neighbour loses the outlier
  CHECK(feature(m, w, 4, 2, "support 15x15") == 1);
  CHECK(feature(m, w, 0, 0, "support 15x15") == 8 * h - 1);  // columns 0..7, less the outlier
  CHECK(feature(m, w, 4, 0, "support 15x15") == w * h - 1);
  CHECK(feature(m, w, 4, 2, "filters changed the level") == 1);
  CHECK(feature(m, w, 6, 3, "row distance to unmatched") == 0);
  CHECK(feature(m, w, 1, 3, "row distance to unmatched") == 5);
  CHECK(feature(m, w, 8, 3, "row distance to unmatched") == 2);
  CHECK(feature(m, w, 1, 0, "row distance to unmatched") == 64);  // no unmatched pixel in the row
  CHECK(feature(m, w, 1, 2, "|Ix| mean 5x5") == 0);               // flat, 3 columns from the edge
  CHECK(feature(m, w, 4, 2, "|Ix| mean 5x5") > 0);
  CHECK(feature(m, w, 1, 2, "grey sd 5x5") == 0);
  CHECK(feature(m, w, 4, 2, "grey sd 5x5") > 0);
}

TEST_CASE("bound forest: learns a shared rule, scored on the frame it did not see") {
  // Three frames; in each, the pixels whose left-right level is off are wrong by 3 levels.
  std::vector<OutputFrame> fr;
  std::vector<cv::Mat> est;
  for (int i = 0; i < 3; ++i) {
    OutputFrame f = flat_frame(40, 30, 8 + i);
    cv::Mat e(30, 40, CV_32F, cv::Scalar(8 + i));
    for (int y = 0; y < 30; ++y)
      for (int x = (y + i) % 3; x < 40; x += 3) {
        f.ev.lr.at(x, y) = static_cast<uint8_t>(8 + i + 5);
        e.at<float>(y, x) += 3.0f;
      }
    fr.push_back(std::move(f));
    est.push_back(e);
  }
  BoundConfig cfg;
  cfg.samples = 3000;
  cfg.trees = 5;
  const auto score = loso_scores(fr, est, cfg);
  REQUIRE(score.size() == 3);
  for (int i = 0; i < 3; ++i) {
    const cv::Mat bad = cv::abs(est[static_cast<size_t>(i)] - fr[static_cast<size_t>(i)].gt) > 1;
    double worst_good = 255, best_bad = 0;
    cv::minMaxLoc(score[static_cast<size_t>(i)], &worst_good, nullptr, nullptr, nullptr, ~bad);
    cv::minMaxLoc(score[static_cast<size_t>(i)], nullptr, &best_bad, nullptr, nullptr, bad);
    CHECK(best_bad < worst_good);
  }
}
