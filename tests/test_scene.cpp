// Synthetic scene generator (toolio/sm_scenegen.*, tools/sm_scene): determinism,
// exactness of the ground truth, camera imperfections and the files it writes.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "calib_file.hpp"
#include "configs.hpp"
#include "pipeline.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_placed_objects.hpp"
#include "toolio/sm_scenegen.hpp"
#include "sm_cmd.hpp"
#include "sm_test_util.hpp"

namespace fs = std::filesystem;
using sm::tools::render_scene;
using sm::tools::SceneParams;

namespace {

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

using sm::test::slurp;

SceneParams small(uint64_t seed = 3) { return sm::test::scene_params(96, 64, 32, seed, 4); }

fs::path scratch(const std::string& name) { return sm::test::fresh_dir(fs::path(SM_TEST_TMP) / name); }

}  // namespace

TEST_CASE("same seed gives the same scene, another seed a different one", "[unit][scene]") {
  const auto a = render_scene(small(3)), b = render_scene(small(3)), c = render_scene(small(4));
  CHECK(same(a.left, b.left));
  CHECK(same(a.right, b.right));
  CHECK(same(a.gt, b.gt));
  CHECK(same(a.nonocc, b.nonocc));
  CHECK_FALSE(same(a.left, c.left));
  CHECK_FALSE(same(a.gt, c.gt));
}

TEST_CASE("sm_scene writes byte-identical files for the same seed", "[unit][scene]") {
  const fs::path d1 = scratch("scene_det1"), d2 = scratch("scene_det2");
  const std::string args = " --width 80 --height 40 --levels 24 --seed 9 --objects 3 --noise 1.5";
  REQUIRE(std::system((std::string("\"") + SM_SCENE_EXE + "\" --out " + d1.string() + args).c_str()) == 0);
  REQUIRE(std::system((std::string("\"") + SM_SCENE_EXE + "\" --out " + d2.string() + args).c_str()) == 0);
  for (const char* f : {"left.png", "right.png", "gt.png", "nonocc.png", "scale.txt", "camera.json", "calib.json"}) {
    INFO(f);
    const std::string a = slurp(d1 / f);
    CHECK(!a.empty());
    CHECK(a == slurp(d2 / f));
  }
  CHECK(slurp(d1 / "scale.txt") == "256 24\n");
}

TEST_CASE("fronto-parallel plane: every visible left pixel is right pixel x - d", "[unit][scene]") {
  for (int d : {0, 1, 7, 13}) {
    SceneParams p = small(11);
    p.objects = 0;
    p.bg_disp = d;
    p.bg_slant_x = 0;
    p.bg_slant_y = 0;
    const auto s = render_scene(p);
    long checked = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        INFO("d=" << d << " x=" << x << " y=" << y);
        REQUIRE(s.gt.at<float>(y, x) == static_cast<float>(d));
        // Visible exactly when the match lies inside the right image (hand-derived).
        REQUIRE((s.nonocc.at<uint8_t>(y, x) != 0) == (x >= d));
        if (x >= d) {
          REQUIRE(s.left.at<uint8_t>(y, x) == s.right.at<uint8_t>(y, x - d));
          ++checked;
        }
      }
    CHECK(checked == static_cast<long>(p.height) * (p.width - d));
    // The texture is not flat (a constant image would pass the check above trivially).
    cv::Scalar mean, dev;
    cv::meanStdDev(s.left, mean, dev);
    CHECK(dev[0] > 15.0);
  }
}

TEST_CASE("scene with objects: visible pixels at integer disparity match exactly", "[unit][scene]") {
  for (uint64_t seed : {1u, 2u, 5u}) {
    SceneParams p = small(seed);
    p.width = 160;
    p.height = 96;
    p.levels = 64;
    p.objects = 5;
    const auto s = render_scene(p);
    long checked = 0, occluded = 0, mismatched_occluded = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const float g = s.gt.at<float>(y, x);
        REQUIRE(g >= 0.0f);
        REQUIRE(g <= p.levels - 1);
        if (g != std::floor(g)) continue;  // slanted background: fractional disparity
        const int d = static_cast<int>(g);
        if (s.nonocc.at<uint8_t>(y, x)) {
          INFO("seed " << seed << " x=" << x << " y=" << y << " d=" << d);
          REQUIRE(x - d >= 0);
          REQUIRE(s.left.at<uint8_t>(y, x) == s.right.at<uint8_t>(y, x - d));
          ++checked;
        } else if (x - d >= 0) {
          ++occluded;
          mismatched_occluded += s.left.at<uint8_t>(y, x) != s.right.at<uint8_t>(y, x - d);
        }
      }
    INFO("seed " << seed);
    CHECK(checked > p.width * p.height / 10);  // the objects cover a good part of the view
    CHECK(occluded > 0);                       // and they occlude something
    // Occluded pixels see another surface in the right view: mostly different intensity.
    CHECK(mismatched_occluded > occluded / 2);
    CHECK(s.max_disp > 0.7 * (p.levels - 1));  // objects spread over the near range
  }
}

TEST_CASE("right camera gain/offset and noise", "[unit][scene]") {
  SceneParams p = small(7);
  const auto clean = render_scene(p);
  SceneParams q = p;
  q.offset_r = 20;
  const auto off = render_scene(q);
  CHECK(same(clean.left, off.left));
  long n = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const int v = clean.right.at<uint8_t>(y, x);
      if (v == 0 || v >= 235) continue;  // clipped before or after the offset
      REQUIRE(off.right.at<uint8_t>(y, x) == v + 20);
      ++n;
    }
  CHECK(n > p.width * p.height / 2);
  q = p;
  q.noise = 2.0;
  const auto noisy = render_scene(q);
  cv::Mat diff;
  cv::subtract(noisy.left, clean.left, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, dev;
  cv::meanStdDev(diff, mean, dev);
  CHECK(std::fabs(mean[0]) < 0.2);
  CHECK(dev[0] > 1.7);
  CHECK(dev[0] < 2.3);
  CHECK(same(noisy.gt, clean.gt));
}

TEST_CASE("vertical shift: raw right image and calibration grid follow the homography", "[unit][scene]") {
  SceneParams p = small(8);
  const auto rect = render_scene(p);
  p.vshift = 3;
  const auto raw = render_scene(p);
  CHECK(same(rect.gt, raw.gt));
  // raw = rect shifted down by 3 rows (integer shift: exact).
  for (int y = 3; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) REQUIRE(raw.right.at<uint8_t>(y, x) == rect.right.at<uint8_t>(y - 3, x));
  // The bottom 3 rows of the rectified view are not seen by the shifted camera.
  for (int x = 10; x < p.width; ++x) CHECK(raw.nonocc.at<uint8_t>(p.height - 1, x) == 0);

  const fs::path d = scratch("scene_vshift");
  sm::tools::write_scene(raw, p, d.string());
  const sm::CalibFile c = sm::load_calib((d / "calib.json").string());
  REQUIRE(c.width == p.width);
  REQUIRE(c.right.gw == sm::RectGrid::points_w(p.width));
  for (int gy = 0; gy < c.right.gh; ++gy)
    for (int gx = 0; gx < c.right.gw; ++gx) {
      const size_t i = static_cast<size_t>(gy) * c.right.gw + gx;
      REQUIRE(c.right.sx[i] == gx * 16 * 32);
      REQUIRE(c.right.sy[i] == (gy * 16 + 3) * 32);
    }
  CHECK(c.left.sx == sm::RectGrid::identity(p.width, p.height).sx);
  CHECK(c.rect_radius_needed >= 3);
}

TEST_CASE("rotation: the raw right image is the rectified one rotated about the centre", "[unit][scene]") {
  SceneParams p = small(12);
  p.objects = 0;
  p.bg_slant_x = 0;
  p.bg_slant_y = 0;
  p.rot_deg = 90;  // exact quarter turn on a square-free grid: check a few hand-derived points
  p.width = 64;
  p.height = 64;
  const auto rect = render_scene([&] {
    SceneParams q = p;
    q.rot_deg = 0;
    return q;
  }());
  const auto raw = render_scene(p);
  // raw(x', y') = rect(x, y) with (x'-c, y'-c) = R(90)(x-c, y-c) = (-(y-c), x-c), c = 31.5.
  long n = 0, eq = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const int xr = 63 - y, yr = x;
      ++n;
      eq += raw.right.at<uint8_t>(yr, xr) == rect.right.at<uint8_t>(y, x);
    }
  CHECK(eq > n * 99 / 100);  // floating-point trig: allow a handful of boundary samples
}

TEST_CASE("written scene reads back through the dataset reader", "[unit][scene]") {
  const SceneParams p = small(21);
  const auto s = render_scene(p);
  const fs::path d = scratch("scene_rw");
  sm::tools::write_scene(s, p, d.string());
  REQUIRE(sm::tools::is_scene_dir(d.string()));
  const auto sc = sm::tools::load_scene(d.string());
  CHECK(sc.scale == 256);
  CHECK(sc.levels == p.levels);
  CHECK(same(sc.left, s.left));
  CHECK(same(sc.right, s.right));
  CHECK(same(sc.nonocc, s.nonocc));
  cv::Mat err;
  cv::absdiff(sc.gt, s.gt, err);
  double mx = 0;
  cv::minMaxLoc(err, nullptr, &mx);
  CHECK(mx <= 0.5 / 256 + 1e-6);
  CHECK(cv::imread((d / "gt.png").string(), cv::IMREAD_ANYDEPTH).depth() == CV_16U);
  // Directory holds only the scene files: no temporary leftovers.
  int files = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    INFO(e.path());
    CHECK(e.path().filename().string()[0] != '.');
    ++files;
  }
  CHECK(files == 7);
}

TEST_CASE("impossible scene parameters are rejected", "[unit][scene]") {
  SceneParams p = small();
  p.width = 8;
  CHECK_THROWS_AS(render_scene(p), std::invalid_argument);
  p = small();
  p.bg_disp = 40;  // beyond levels - 1 = 31
  CHECK_THROWS_AS(render_scene(p), std::invalid_argument);
  p = small();
  p.noise = -1;
  CHECK_THROWS_AS(render_scene(p), std::invalid_argument);
}

// The object list of the model at the defaults against the generator's own list of the
// objects it placed (issue 39), on the built-in scene (build/scene: 320x240, 128 levels,
// seed 1, 6 objects) at the paper configuration: every placed object with at least
// OBJ_MIN_PIXELS visible pixels at or above OBJ_NEAR is reported (a listed object at its
// disparity, +-2, whose box meets the object's), and the label table never fills. (The
// small scene is left out: at 64x48 the matcher finds two of its three objects at
// disparity 1-2, so there is nothing for the labeller to report.)
TEST_CASE("scene objects: the model reports every object the generator placed", "[unit][objects]") {
  const SceneParams p = sm::test::scene_params(320, 240, 128, 1, 6);
  // the paper configuration, and zynq's with its speckle stage (a speckle is never an
  // object) at its defaults, the speckle mode (its trusted regions keep the object at
  // disparity 57 with 258 visible pixels, under SPECKLE_SIZE), and with the paper's
  // per-pixel rules instead
  sm::HwConfig hw = sm::named_config("paper");
  bool pixel_rules = false;
  SECTION("paper") {}
  SECTION("zynq") { hw = sm::named_config("zynq"); }
  SECTION("zynq, per-pixel rules") {
    hw = sm::named_config("zynq");
    pixel_rules = true;
  }
  const sm::tools::SyntheticScene s = render_scene(p);
  sm::Regs r = sm::Regs::defaults(hw);
  CHECK(r.speckle_en == (hw.speckle_rows > 0));  // the stage resets into its speckle mode
  if (pixel_rules) sm::set_checked_rules(r, false);
  const sm::PipelineResult res = sm::tools::run_on_scene(p, s, hw, r);
  CHECK_FALSE(res.objects.table_full);
  const std::vector<sm::tools::PlacedCheck> checks =
      sm::tools::check_placed_objects(p, s, res, r.obj_min_pixels, r.obj_near);
  REQUIRE(static_cast<int>(checks.size()) == p.objects);
  int checked = 0;
  for (const sm::tools::PlacedCheck& c : checks) {
    if (!c.counts) continue;
    ++checked;
    INFO("object at disparity " << c.obj.disp << ", box (" << c.x0 << "," << c.y0 << ")-(" << c.x1 << "," << c.y1
                                << "), " << c.visible << " visible pixels");
    CHECK(c.found);
  }
  CHECK(checked == p.objects);  // every placed object is large and near enough to count
}
