// The host's speckle check (toolio/sm_host_speckle.hpp) on float disparities: known
// answers for the size and the difference in 1/16 px, invalid pixels left alone, and on
// random sub-pixel maps the verdict of the study's own union-find (tools/sm_speckle.hpp,
// independent of OpenCV's filterSpeckles, which the host check calls).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "sm_speckle.hpp"
#include "toolio/sm_host_speckle.hpp"

using sm::tools::host_speckle;

namespace {

// A 12 x 10 plane at 10 px with a 2 x 3 island at `island` px in it.
cv::Mat plane_with_island(float island) {
  cv::Mat d(10, 12, CV_32F, cv::Scalar(10.0f));
  d(cv::Rect(4, 3, 2, 3)).setTo(island);
  return d;
}

}  // namespace

TEST_CASE("host speckle check: size and difference known answers", "[speckle]") {
  SECTION("an island of 6 px goes at SIZE 6, stays at SIZE 5") {
    cv::Mat d = plane_with_island(20.0f);
    CHECK(host_speckle(d, 6, 8) == 6);
    CHECK(cv::countNonZero(d < 0) == 6);
    CHECK(d.at<float>(3, 4) == -1.0f);
    CHECK(d.at<float>(0, 0) == 10.0f);  // the plane (114 px) stays
    cv::Mat e = plane_with_island(20.0f);
    CHECK(host_speckle(e, 5, 8) == 0);
  }
  SECTION("half a pixel joins the plane at DIFF 8, not at DIFF 7") {
    cv::Mat d = plane_with_island(10.5f);
    CHECK(host_speckle(d, 6, 8) == 0);
    cv::Mat e = plane_with_island(10.5f);
    CHECK(host_speckle(e, 6, 7) == 6);
  }
  SECTION("SIZE 0 changes nothing") {
    cv::Mat d = plane_with_island(20.0f);
    CHECK(host_speckle(d, 0, 8) == 0);
    CHECK(cv::countNonZero(d < 0) == 0);
  }
  SECTION("invalid pixels stay as they were and split regions") {
    cv::Mat d = plane_with_island(10.0f);  // one plane
    d.col(6).setTo(-2.0f);                 // kNoMatchDisp: the plane splits into 60 + 50 px
    d.at<float>(0, 6) = std::numeric_limits<float>::infinity();
    d.at<float>(1, 6) = std::numeric_limits<float>::quiet_NaN();
    CHECK(host_speckle(d, 55, 8) == 50);
    CHECK(d.at<float>(5, 6) == -2.0f);
    CHECK(std::isinf(d.at<float>(0, 6)));
    CHECK(std::isnan(d.at<float>(1, 6)));
    CHECK(d.at<float>(0, 0) == 10.0f);
    CHECK(d.at<float>(0, 11) == -1.0f);
  }
}

TEST_CASE("host speckle check equals the study's union-find on random sub-pixel maps", "[speckle]") {
  for (const uint64_t seed : {1u, 2u, 3u}) {
    cv::RNG rng(seed);
    cv::Mat d(29, 41, CV_32F), q4(29, 41, CV_16S);
    for (int y = 0; y < d.rows; ++y)
      for (int x = 0; x < d.cols; ++x) {
        const bool invalid = rng.uniform(0, 5) == 0;
        const int v = 8 * rng.uniform(0, 5) + rng.uniform(0, 3);  // levels 1/16 px apart: DIFF matters
        d.at<float>(y, x) = invalid ? -1.0f : static_cast<float>(v) / 16.0f;
        q4.at<int16_t>(y, x) = invalid ? int16_t{-16} : static_cast<int16_t>(v);
      }
    for (const int size : {1, 7, 40})
      for (const int diff : {0, 2, 8}) {
        INFO("seed " << seed << " size " << size << " diff " << diff);
        cv::Mat got = d.clone();
        const long cleared = host_speckle(got, size, diff);
        const cv::Mat keep = sm::tools::speckle_keep(q4, size, diff, q4.rows);
        long want = 0;
        for (int y = 0; y < d.rows; ++y)
          for (int x = 0; x < d.cols; ++x) {
            const bool valid = d.at<float>(y, x) >= 0;
            const bool kept = keep.at<uint8_t>(y, x) != 0;
            want += valid && !kept;
            CHECK(got.at<float>(y, x) == (valid && !kept ? -1.0f : d.at<float>(y, x)));
          }
        CHECK(cleared == want);
      }
  }
}
