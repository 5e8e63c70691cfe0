// Model tests of the pre-processing stages (docs/algorithm.md, sections 1-2) and the
// calibration file, against hand-computed answers and OpenCV.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calib_file.hpp"
#include "pre.hpp"
#include "sm_test_util.hpp"
#include "toolio/sm_io.hpp"

namespace {

sm::Image8 smooth_image(int w, int h) {
  sm::Image8 img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = static_cast<uint8_t>(
          std::lround(128 + 60 * std::sin(x / 7.0) * std::cos(y / 9.0) + 30 * std::sin((x + y) / 13.0)));
  return img;
}

using sm::tools::to_mat;  // Image8 -> CV_8UC1 (toolio, as the tools convert)

sm::RectGrid shifted_identity(int w, int h, int dx_q5, int dy_q5) {
  sm::RectGrid g = sm::RectGrid::identity(w, h);
  for (auto& v : g.sx) v = static_cast<int16_t>(v + dx_q5);
  for (auto& v : g.sy) v = static_cast<int16_t>(v + dy_q5);
  return g;
}

sm::HwConfig hw_with_radius(int r) {
  sm::HwConfig hw;
  hw.rect_radius = r;
  return hw;
}

struct Diff {
  double mean = 0;
  int max = 0;
  long n = 0;
};

// |a - b| over pixels where mask is set.
Diff compare(const sm::Image8& a, const cv::Mat& b, const cv::Mat& mask) {
  Diff d;
  double sum = 0;
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x) {
      if (!mask.at<uint8_t>(y, x)) continue;
      const int e = std::abs(a.at(x, y) - b.at<uint8_t>(y, x));
      sum += e;
      d.max = std::max(d.max, e);
      ++d.n;
    }
  d.mean = d.n ? sum / static_cast<double>(d.n) : 0;
  return d;
}

// Pixels whose source position lies at least `margin` px inside the image.
cv::Mat inner_mask(const cv::Mat& mapx, const cv::Mat& mapy, int w, int h, float margin) {
  cv::Mat m(h, w, CV_8U, cv::Scalar(0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float sx = mapx.at<float>(y, x), sy = mapy.at<float>(y, x);
      m.at<uint8_t>(y, x) = sx >= margin && sx <= w - 1 - margin && sy >= margin && sy <= h - 1 - margin;
    }
  return m;
}

std::vector<float> to_vec(const cv::Mat& m) {
  std::vector<float> v;
  v.assign(m.begin<float>(), m.end<float>());
  return v;
}

}  // namespace

TEST_CASE("brightness known answers", "[unit]") {
  sm::Image8 in(8, 1);
  const uint8_t vals[8] = {0, 1, 3, 100, 128, 200, 254, 255};
  for (int i = 0; i < 8; ++i) in.px[i] = vals[i];
  // identity
  CHECK(sm::brightness(in, 256, 0) == in);
  // gain 0.5: (v*128 + 128) >> 8 rounds half up: 1 -> 1, 3 -> 2, 255 -> 128
  auto h = sm::brightness(in, 128, 0);
  CHECK(std::vector<int>(h.px.begin(), h.px.end()) == std::vector<int>{0, 1, 2, 50, 64, 100, 127, 128});
  // gain 1.5 saturates at 255; offset +10
  auto g = sm::brightness(in, 384, 10);
  CHECK(std::vector<int>(g.px.begin(), g.px.end()) == std::vector<int>{10, 12, 15, 160, 202, 255, 255, 255});
  // offset -256 clamps everything to 0, +255 clamps to 255 except nothing below
  auto lo = sm::brightness(in, 1023, -256);
  CHECK(std::vector<int>(lo.px.begin(), lo.px.end()) == std::vector<int>{0, 0, 0, 144, 255, 255, 255, 255});
  auto hi = sm::brightness(in, 0, 255);
  for (auto p : hi.px) CHECK(p == 255);
  // the offset register is 9 bits two's complement: 0x1ff is -1
  CHECK(sm::brightness(in, 256, static_cast<int16_t>(0x1ff)).px[3] == 99);
}

TEST_CASE("brightness matches OpenCV convertTo away from rounding ties", "[unit]") {
  sm::Image8 in(256, 1);
  for (int i = 0; i < 256; ++i) in.px[i] = static_cast<uint8_t>(i);
  const cv::Mat m = to_mat(in);
  for (int gain : {0, 1, 77, 200, 256, 300, 511, 777, 1023})
    for (int off : {-256, -40, 0, 17, 255}) {
      cv::Mat ref;
      m.convertTo(ref, CV_8U, gain / 256.0, off);
      const auto out = sm::brightness(in, static_cast<uint16_t>(gain), static_cast<int16_t>(off));
      for (int v = 0; v < 256; ++v) {
        if (((v * gain) & 255) == 128) continue;  // OpenCV rounds ties to even, we round up
        INFO("v " << v << " gain " << gain << " off " << off);
        CHECK(out.px[v] == ref.at<uint8_t>(0, v));
      }
    }
}

TEST_CASE("rectify identity, passthrough and hand-computed shifts", "[unit]") {
  const int w = 37, h = 29;
  sm::Image8 in(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) in.at(x, y) = static_cast<uint8_t>((x * 7 + y * 13) & 255);
  const auto hw = hw_with_radius(4);
  CHECK(sm::rectify(in, sm::RectGrid{}, true, hw) == in);
  CHECK(sm::rectify(in, sm::RectGrid::identity(w, h), true, hw) == in);
  // enable = 0 ignores the grid
  CHECK(sm::rectify(in, shifted_identity(w, h, 99, 45), false, hw) == in);

  // integer shift (+3, -2): out(x, y) = in(x + 3, y - 2), 0 outside
  auto s = sm::rectify(in, shifted_identity(w, h, 3 * 32, -2 * 32), true, hw);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int sx = x + 3, sy = y - 2;
      const int want = (sx < w && sy >= 0) ? in.at(sx, sy) : 0;
      INFO("x " << x << " y " << y);
      REQUIRE(s.at(x, y) == want);
    }
  // half-pixel shift in x: (a * 128 + b * 128 + 128) >> 8 = (a + b + 1) >> 1
  auto half = sm::rectify(in, shifted_identity(w, h, 16, 0), true, hw);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x + 1 < w; ++x) REQUIRE(half.at(x, y) == ((in.at(x, y) + in.at(x + 1, y) + 1) >> 1));
  // last column: the right tap is outside -> (a * 128 + 128) >> 8
  CHECK(half.at(w - 1, 5) == ((in.at(w - 1, 5) * 128 + 128) >> 8));
}

TEST_CASE("rectify window rule: rows beyond RECT_RADIUS read 0", "[unit]") {
  const int w = 40, h = 40;
  sm::Image8 in(w, h, 200);
  // shift down by exactly R rows: every tap inside the window
  auto a = sm::rectify(in, shifted_identity(w, h, 0, 4 * 32), true, hw_with_radius(4));
  CHECK(a.at(10, 10) == 200);
  // R + 1 rows: the only tap is outside the window
  auto b = sm::rectify(in, shifted_identity(w, h, 0, 5 * 32), true, hw_with_radius(4));
  CHECK(b.at(10, 10) == 0);
  // R + 0.5 rows: row y+R counts, row y+R+1 does not -> (200*128 + 128) >> 8 = 100
  auto c = sm::rectify(in, shifted_identity(w, h, 0, 4 * 32 + 16), true, hw_with_radius(4));
  CHECK(c.at(10, 10) == 100);
}

TEST_CASE("rect_radius_needed", "[unit]") {
  const int w = 64, h = 48;
  CHECK(sm::rect_radius_needed(sm::RectGrid::identity(w, h), w, h) == 0);
  // integer shift by 3 rows: one tap row, 3 away
  CHECK(sm::rect_radius_needed(shifted_identity(w, h, 0, 3 * 32), w, h) == 3);
  // 3.5 rows: the second bilinear row is 4 away
  CHECK(sm::rect_radius_needed(shifted_identity(w, h, 0, 3 * 32 + 16), w, h) == 4);
  CHECK(sm::rect_radius_needed(shifted_identity(w, h, 0, -(6 * 32 + 8)), w, h) == 7);
  // sources entirely left of the image need no rows at all
  CHECK(sm::rect_radius_needed(shifted_identity(w, h, -100 * 32, 9 * 32), w, h) == 0);

  // a tilted map: with the reported radius the window rule changes nothing, one less does
  sm::RectGrid g = sm::RectGrid::identity(w, h);
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx)
      g.sy[static_cast<size_t>(gy) * g.gw + gx] = static_cast<int16_t>((16 * gy + gx * 1.7 - 2.3) * 32);
  const int need = sm::rect_radius_needed(g, w, h);
  const auto img = smooth_image(w, h);
  REQUIRE(need >= 2);
  REQUIRE(need < 31);
  CHECK(sm::rectify(img, g, true, hw_with_radius(need)) == sm::rectify(img, g, true, hw_with_radius(31)));
  CHECK(sm::rectify(img, g, true, hw_with_radius(need - 1)) != sm::rectify(img, g, true, hw_with_radius(31)));
}

TEST_CASE("grid_from_maps samples, rounds to Q.5 and saturates", "[unit]") {
  const int w = 37, h = 20;  // grid 4 x 3 points, extent 49 x 33
  const int mw = 49, mh = 33;
  std::vector<float> mx(mw * mh), my(mw * mh);
  for (int y = 0; y < mh; ++y)
    for (int x = 0; x < mw; ++x) {
      mx[y * mw + x] = x + 0.3f;          // 0.3 px = 9.6/32 -> 10
      my[y * mw + x] = y * 2.0f - 0.51f;  // -0.51 px = -16.32/32 -> -16
    }
  mx[32 * mw + 48] = 5000.f;   // saturates high
  my[32 * mw + 48] = -5000.f;  // saturates low
  const auto g = sm::grid_from_maps(mx, my, mw, mh, w, h);
  REQUIRE(g.gw == 4);
  REQUIRE(g.gh == 3);
  CHECK(g.sx[0] == 10);
  CHECK(g.sy[0] == -16);
  CHECK(g.sx[1 * 4 + 2] == 32 * 32 + 10);
  CHECK(g.sy[1 * 4 + 2] == 32 * 32 - 16);
  CHECK(g.sx[2 * 4 + 3] == 32767);
  CHECK(g.sy[2 * 4 + 3] == -32768);
  // a map smaller than the grid extent is rejected
  CHECK_THROWS_AS(sm::grid_from_maps(std::vector<float>(48 * 33), std::vector<float>(48 * 33), 48, 33, w, h),
                  std::invalid_argument);
  // a grid of the wrong size is rejected by rectify
  CHECK_THROWS_AS(sm::rectify(sm::Image8(w, h), sm::RectGrid::identity(w + 16, h), true, hw_with_radius(4)),
                  std::invalid_argument);
}

TEST_CASE("rectify of a homography matches OpenCV warpPerspective", "[unit]") {
  const int w = 320, h = 240;
  const auto img = smooth_image(w, h);
  const cv::Matx33d hm(1.02, 0.03, -4.0, -0.025, 0.99, 3.5, 2e-5, -3e-5, 1.0);
  // dense map at the grid extent: source = hm * (x, y, 1)
  const int gw = sm::RectGrid::points_w(w), gh = sm::RectGrid::points_h(h);
  const int mw = (gw - 1) * 16 + 1, mh = (gh - 1) * 16 + 1;
  cv::Mat mapx(mh, mw, CV_32F), mapy(mh, mw, CV_32F);
  for (int y = 0; y < mh; ++y)
    for (int x = 0; x < mw; ++x) {
      const cv::Vec3d p = hm * cv::Vec3d(x, y, 1);
      mapx.at<float>(y, x) = static_cast<float>(p[0] / p[2]);
      mapy.at<float>(y, x) = static_cast<float>(p[1] / p[2]);
    }
  const auto grid = sm::grid_from_maps(to_vec(mapx), to_vec(mapy), mw, mh, w, h);
  const int need = sm::rect_radius_needed(grid, w, h);
  INFO("radius needed " << need);
  REQUIRE(need <= 15);
  const auto out = sm::rectify(img, grid, true, hw_with_radius(15));
  cv::Mat ref;
  cv::warpPerspective(to_mat(img), ref, cv::Mat(hm), cv::Size(w, h), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                      cv::BORDER_CONSTANT, 0);
  const Diff d = compare(out, ref, inner_mask(mapx(cv::Rect(0, 0, w, h)), mapy(cv::Rect(0, 0, w, h)), w, h, 1));
  std::printf("homography vs warpPerspective: %ld px, mean |diff| %.3f, max %d\n", d.n, d.mean, d.max);
  REQUIRE(d.n > w * h / 2);
  CHECK(d.mean <= 1.0);
  CHECK(d.max <= 4);
}

TEST_CASE("rectify of a distorted camera matches OpenCV initUndistortRectifyMap + remap", "[unit]") {
  const int w = 320, h = 240;
  const auto img = smooth_image(w, h);  // stands for the distorted camera image
  const cv::Matx33d k(300, 0, 161.5, 0, 302, 118.2, 0, 0, 1);
  const cv::Mat dist = (cv::Mat_<double>(1, 5) << -0.27, 0.07, 0.0012, -0.0009, 0.0);
  cv::Mat rot;
  cv::Rodrigues(cv::Vec3d(0.012, -0.02, 0.004), rot);
  const cv::Matx34d p(265, 0, 158, 0, 0, 265, 121, 0, 0, 0, 1, 0);
  const int gw = sm::RectGrid::points_w(w), gh = sm::RectGrid::points_h(h);
  const int mw = (gw - 1) * 16 + 1, mh = (gh - 1) * 16 + 1;
  cv::Mat mapx, mapy;
  cv::initUndistortRectifyMap(k, dist, rot, p, cv::Size(mw, mh), CV_32FC1, mapx, mapy);
  const auto grid = sm::grid_from_maps(to_vec(mapx), to_vec(mapy), mw, mh, w, h);
  const cv::Mat mx = mapx(cv::Rect(0, 0, w, h)), my = mapy(cv::Rect(0, 0, w, h));

  // the grid reproduces the dense map far below a pixel (the spec's justification)
  // (strongest in the corners, where k1 = -0.27 bends the map most)
  double max_err = 0, sum_err = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int sx, sy;
      sm::rect_source_q4(grid, x, y, sx, sy);
      const double e = std::max(std::fabs(sx / 16.0 - mx.at<float>(y, x)), std::fabs(sy / 16.0 - my.at<float>(y, x)));
      max_err = std::max(max_err, e);
      sum_err += e;
    }
  const int need = sm::rect_radius_needed(grid, w, h);
  std::printf("distortion map: grid position error mean %.4f max %.4f px, radius needed %d\n", sum_err / (w * h),
              max_err, need);
  CHECK(sum_err / (w * h) <= 0.1);
  CHECK(max_err <= 0.25);

  const auto out = sm::rectify(img, grid, true, hw_with_radius(31));
  cv::Mat ref;
  cv::remap(to_mat(img), ref, mx, my, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  const Diff d = compare(out, ref, inner_mask(mx, my, w, h, 1));
  std::printf("distortion vs remap: %ld px, mean |diff| %.3f, max %d\n", d.n, d.mean, d.max);
  REQUIRE(d.n > w * h / 2);
  CHECK(d.mean <= 1.0);
  CHECK(d.max <= 5);
}

TEST_CASE("calibration file round trip and errors", "[unit]") {
  sm::CalibFile c;
  c.width = 37;
  c.height = 20;
  c.rect_radius_needed = 3;
  c.left = shifted_identity(37, 20, 5, -7);
  c.right = sm::RectGrid::identity(37, 20);
  c.right.sx[3] = -32768;
  // the calibration files of this test, in a scratch folder of the build
  const std::filesystem::path dir = sm::test::fresh_dir(std::filesystem::path(SM_TEST_TMP) / "calib");
  auto in_dir = [&](const std::string& name) { return (dir / name).string(); };
  const std::string path = in_dir("test_pre_model_calib.json");
  sm::save_calib(path, c);
  const auto l = sm::load_calib(path);
  CHECK(l.width == 37);
  CHECK(l.height == 20);
  CHECK(l.rect_radius_needed == 3);
  CHECK(l.left.sx == c.left.sx);
  CHECK(l.left.sy == c.left.sy);
  CHECK(l.right.sx == c.right.sx);
  CHECK(l.right.gw == 4);

  auto expect_error = [](const std::string& file, const std::string& what) {
    try {
      sm::load_calib(file);
      FAIL("no error for " << what);
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find(file) != std::string::npos);
      CHECK(msg.find(what) != std::string::npos);
    }
  };
  expect_error(in_dir("does_not_exist.json"), "cannot open");
  std::string text;
  {
    std::ifstream f(path);
    text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  auto write = [](const std::string& file, const std::string& s) { std::ofstream(file) << s; };
  write(in_dir("calib_trunc.json"), text.substr(0, text.size() / 2));
  expect_error(in_dir("calib_trunc.json"), "malformed JSON");
  write(in_dir("calib_garbage.json"), "hello");
  expect_error(in_dir("calib_garbage.json"), "malformed JSON");
  {
    auto j = text;
    const auto pos = j.find("\"width\": 37");
    REQUIRE(pos != std::string::npos);
    j.replace(pos, 11, "\"width\": 60");  // grid no longer fits the width
    write(in_dir("calib_size.json"), j);
    expect_error(in_dir("calib_size.json"), "grid size");
  }
  {
    sm::CalibFile bad = c;
    bad.left.sx.pop_back();  // a short array
    sm::save_calib(in_dir("calib_short.json"), bad);
    expect_error(in_dir("calib_short.json"), "left.sx");
  }
  write(in_dir("calib_missing.json"), "{\"format\": \"sm_calib\", \"version\": 1}");
  expect_error(in_dir("calib_missing.json"), "missing key 'width'");
}
