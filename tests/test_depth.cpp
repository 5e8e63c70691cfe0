// Metric depth, point clouds and pictures (toolio/sm_depth, toolio/sm_pictures), the
// calibration file's camera and checks (model/calib_file), temporary files removed on
// SIGINT/SIGTERM (toolio/sm_signal_cleanup), and the tools that use them end to end:
// sm_scene --focal-px/--baseline-m -> stereo_model --depth-file/--cloud against the
// scene's exact depth ([system]), sm_calibrate's and the calibration file's bad inputs
// ([robust]). The PLY is read back by an independent reader in tests/depth_cloud_check.py.

#include <fmt/format.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "calib_file.hpp"
#include "toolio/sm_depth.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_pictures.hpp"
#include "toolio/sm_signal_cleanup.hpp"
#include "sm_chessboard_rig.hpp"
#include "sm_cmd.hpp"
#include "sm_test_util.hpp"

namespace fs = std::filesystem;
using sm::RectCamera;
using sm::tools::CloudPoint;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// One folder per process: the unit, system and robust runs of this binary (tests/depth.cmake)
// run side by side under ctest -j and must not remove each other's files.
fs::path tmp_root() {
  struct Root {
    fs::path p = fs::path(SM_TEST_TMP) / std::to_string(::getpid());
    ~Root() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  };
  static const Root r;
  return r.p;
}

sm::test::CmdResult run(const std::string& exe, const std::string& args) {
  fs::create_directories(tmp_root());
  return sm::test::run_cmd(exe, args, tmp_root());
}

// Non-zero exit, exactly one line on stderr "<tool>: error: ..." mentioning `what`.
void expect_error(const sm::test::CmdResult& r, const std::string& tool, const std::string& what) {
  INFO("stderr: " << r.err);
  CHECK(r.rc != 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.rfind(tool + ": error: ", 0) == 0);
  CHECK(r.err.find(what) != std::string::npos);
}

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

const RectCamera kCam{500.0, 159.5, 119.5, 0.12};

// A 40x20 calibration at the identity whose rig needs `radius` line-buffer rows.
sm::CalibFile identity_calib_40x20(int radius) {
  sm::CalibFile c;
  c.width = 40;
  c.height = 20;
  c.rect_radius_needed = radius;
  c.left = sm::RectGrid::identity(40, 20);
  c.right = c.left;
  return c;
}

}  // namespace

TEST_CASE("disparity_to_depth: Z = f B / d, invalid for d <= 0 or not finite", "[unit][depth]") {
  cv::Mat d = (cv::Mat_<float>(1, 7) << 10.f, 60.f, 12.5f, 0.f, -1.f, NAN, kInf);
  const cv::Mat z = sm::tools::disparity_to_depth(d, kCam);
  CHECK(z.at<float>(0, 0) == Approx(6.0));  // 500 * 0.12 / 10
  CHECK(z.at<float>(0, 1) == Approx(1.0));
  CHECK(z.at<float>(0, 2) == Approx(4.8));  // sub-pixel disparity
  for (int i = 3; i < 7; ++i) CHECK(std::isinf(z.at<float>(0, i)));
}

TEST_CASE("depth_to_cloud back-projects through the principal point", "[unit][depth]") {
  const RectCamera cam{100.0, 1.0, 2.0, 0.5};
  cv::Mat z(3, 4, CV_32F, cv::Scalar(kInf)), grey(3, 4, CV_8UC1, cv::Scalar(7));
  z.at<float>(2, 1) = 2.0f;  // on the principal point: X = Y = 0
  z.at<float>(0, 3) = 4.0f;  // X = (3 - 1) * 4 / 100, Y = (0 - 2) * 4 / 100
  z.at<float>(1, 0) = 9.0f;  // cut by max_depth 5
  grey.at<uint8_t>(0, 3) = 200;
  const auto all = sm::tools::depth_to_cloud(z, grey, cam);
  REQUIRE(all.size() == 3);
  const auto pts = sm::tools::depth_to_cloud(z, grey, cam, 5.0);
  REQUIRE(pts.size() == 2);
  CHECK(pts[0].x == Approx(0.08));  // raster order: (3, 0) first
  CHECK(pts[0].y == Approx(-0.08));
  CHECK(pts[0].z == Approx(4.0));
  CHECK(pts[0].grey == 200);
  CHECK(pts[1].x == Approx(0.0));
  CHECK(pts[1].y == Approx(0.0).margin(1e-7));
  CHECK(pts[1].z == Approx(2.0));
  CHECK(pts[1].grey == 7);
}

TEST_CASE("depth files: PFM metres and PNG millimetres round trip, 0 / inf = invalid", "[unit][depth]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "depth_files");
  cv::Mat z = (cv::Mat_<float>(2, 3) << 1.2345f, 0.0004f, 70.0f, kInf, 3.0f, 65.535f);
  const std::string pfm = (dir / "z.pfm").string(), png = (dir / "z.PNG").string();
  sm::tools::write_depth_file(pfm, z);
  sm::tools::write_depth_file(png, z);
  const cv::Mat a = sm::tools::read_depth_file(pfm), b = sm::tools::read_depth_file(png);
  CHECK(a.at<float>(0, 0) == 1.2345f);  // float: exact
  CHECK(a.at<float>(0, 2) == 70.0f);
  CHECK(std::isinf(a.at<float>(1, 0)));
  const cv::Mat mm = cv::imread(png, cv::IMREAD_UNCHANGED);
  REQUIRE(mm.type() == CV_16UC1);
  CHECK(mm.at<uint16_t>(0, 0) == 1235);  // round(1234.5)
  CHECK(mm.at<uint16_t>(0, 1) == 0);     // below half a millimetre
  CHECK(mm.at<uint16_t>(0, 2) == 0);     // beyond 65.535 m: not representable
  CHECK(mm.at<uint16_t>(1, 0) == 0);
  CHECK(mm.at<uint16_t>(1, 1) == 3000);
  CHECK(mm.at<uint16_t>(1, 2) == 65535);
  CHECK(b.at<float>(1, 1) == Approx(3.0));
  CHECK(std::isinf(b.at<float>(0, 2)));
  CHECK_THROWS_WITH(sm::tools::write_depth_file((dir / "z.tif").string(), z), Catch::Contains("z.tif"));
}

TEST_CASE("write_ply: header and 13-byte little-endian records", "[unit][depth]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "ply");
  const std::vector<CloudPoint> pts = {{1.5f, -2.25f, 3.0f, 9}, {0.f, 0.f, 1e-3f, 255}};
  const std::string path = (dir / "c.ply").string();
  sm::tools::write_ply(path, pts);
  const std::string bytes = sm::test::slurp(path);
  const std::string end = "end_header\n";
  const size_t body = bytes.find(end) + end.size();
  const std::string header = bytes.substr(0, body);
  CHECK(header.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
  CHECK(header.find("element vertex 2\n") != std::string::npos);
  CHECK(header.find("property float x\nproperty float y\nproperty float z\nproperty uchar intensity\n") !=
        std::string::npos);
  REQUIRE(bytes.size() == body + 2 * 13);
  // 1.5f = 0x3fc00000, -2.25f = 0xc0100000, little-endian
  CHECK(std::memcmp(bytes.data() + body, "\x00\x00\xc0\x3f\x00\x00\x10\xc0", 8) == 0);
  CHECK(static_cast<uint8_t>(bytes[body + 12]) == 9);
  CHECK(static_cast<uint8_t>(bytes[body + 25]) == 255);
  CHECK(listing(dir) == std::vector<std::string>{"c.ply"});  // no temporary left
}

TEST_CASE("calibration file: the camera round trips; unknown keys and bad values are named", "[unit][depth]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "calib_file");
  sm::CalibFile c = identity_calib_40x20(4);
  const std::string plain = (dir / "plain.json").string(), cam = (dir / "cam.json").string();
  sm::save_calib(plain, c);
  CHECK_FALSE(sm::load_calib(plain).camera.has_value());
  c.camera = RectCamera{321.5, 19.5, 9.25, 0.0625};
  sm::save_calib(cam, c);
  const sm::CalibFile l = sm::load_calib(cam);
  REQUIRE(l.camera.has_value());
  CHECK(l.camera->f_px == 321.5);
  CHECK(l.camera->cx == 19.5);
  CHECK(l.camera->cy == 9.25);
  CHECK(l.camera->baseline_m == 0.0625);

  nlohmann::json j;
  std::ifstream(cam) >> j;
  auto expect_bad = [&](const nlohmann::json& bad, const std::string& what) {
    const std::string p = (dir / "bad.json").string();
    std::ofstream(p) << bad.dump();
    try {
      sm::load_calib(p);
      FAIL("accepted: " << what);
    } catch (const std::runtime_error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(p) != std::string::npos);
      CHECK(std::string(e.what()).find(what) != std::string::npos);
    }
  };
  auto with = [&](const char* k, const nlohmann::json& v) {
    nlohmann::json b = j;
    b[k] = v;
    return b;
  };
  expect_bad(with("rect_radius", 3), "unknown key 'rect_radius'");
  nlohmann::json b = j;
  b["left"]["sz"] = 1;
  expect_bad(b, "unknown key 'left.sz'");
  b = j;
  b["camera"]["focal"] = 1;
  expect_bad(b, "unknown key 'camera.focal'");
  b = j;
  b["camera"]["f_px"] = -3;
  expect_bad(b, "'camera.f_px' = -3");
  b = j;
  b["camera"].erase("baseline_m");
  expect_bad(b, "missing key 'camera.baseline_m'");
  b = j;
  b["camera"]["cx"] = "x";
  expect_bad(b, "'camera.cx' is not a number");

  sm::HwConfig hw;
  hw.rect_radius = 3;
  CHECK_THROWS_WITH(sm::check_calib_fits("f.json", l, hw), Catch::Contains("f.json") &&
                                                               Catch::Contains("'rect_radius_needed' = 4") &&
                                                               Catch::Contains("RECT_RADIUS 3"));
  hw.rect_radius = 4;
  CHECK_NOTHROW(sm::check_calib_fits("f.json", l, hw));
}

TEST_CASE("load_fitting_calib: loads a file the IP holds, refuses a larger radius naming the file", "[unit][depth]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "fitting_calib");
  sm::CalibFile c = identity_calib_40x20(4);
  c.right.sx[3] = 77;  // not the identity: the file's grids come back, not the defaults
  c.camera = RectCamera{321.5, 19.5, 9.25, 0.0625};
  const std::string fits = (dir / "fits.json").string(), wide = (dir / "wide.json").string();
  sm::save_calib(fits, c);
  c.rect_radius_needed = 5;
  sm::save_calib(wide, c);

  sm::HwConfig hw;
  hw.rect_radius = 4;
  const sm::CalibFile l = sm::load_fitting_calib(fits, hw);
  CHECK(l.width == 40);
  CHECK(l.height == 20);
  CHECK(l.rect_radius_needed == 4);
  CHECK(l.right.sx == c.right.sx);
  CHECK(l.left.sy == c.left.sy);
  REQUIRE(l.camera.has_value());
  CHECK(l.camera->f_px == 321.5);
  CHECK_THROWS_WITH(sm::load_fitting_calib(wide, hw), Catch::Contains(wide) &&
                                                          Catch::Contains("'rect_radius_needed' = 5") &&
                                                          Catch::Contains("RECT_RADIUS 4"));
  hw.rect_radius = 5;
  CHECK(sm::load_fitting_calib(wide, hw).rect_radius_needed == 5);
  // the loader's own errors come through unchanged
  const std::string missing = (dir / "missing.json").string();
  CHECK_THROWS_WITH(sm::load_fitting_calib(missing, hw),
                    Catch::Contains(missing) && Catch::Contains("cannot open calibration file"));
}

TEST_CASE("pictures: data range, invalid colour, colour bar, legends, object labels, cloud view", "[unit][pictures]") {
  cv::Mat d(40, 60, CV_32F);
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) d.at<float>(y, x) = 20.0f + x * 0.5f;
  d.at<float>(0, 0) = -1;
  d.at<float>(1, 0) = NAN;
  d.at<float>(2, 0) = sm::tools::kNoMatchDisp;  // occluded or left of the border
  const sm::tools::ColourRange r = sm::tools::data_range(d);
  CHECK(r.lo == Approx(20.0));
  CHECK(r.hi == Approx(49.5));
  const cv::Mat c = sm::tools::colourise(d, r);
  CHECK(c.at<cv::Vec3b>(0, 0) == cv::Vec3b(255, 255, 255));
  CHECK(c.at<cv::Vec3b>(1, 0) == cv::Vec3b(255, 255, 255));
  CHECK(c.at<cv::Vec3b>(2, 0) == cv::Vec3b(128, 128, 128));
  // the ends of the range are the ends of the turbo map, which is never white
  cv::Mat ends = (cv::Mat_<uint8_t>(1, 2) << 0, 255), turbo;
  cv::applyColorMap(ends, turbo, cv::COLORMAP_TURBO);
  CHECK(c.at<cv::Vec3b>(5, 0) == turbo.at<cv::Vec3b>(0, 0));
  CHECK(c.at<cv::Vec3b>(5, 59) == turbo.at<cv::Vec3b>(0, 1));
  for (int i = 0; i < 256; ++i) {
    cv::Mat one(1, 1, CV_8UC1, cv::Scalar(i)), col;
    cv::applyColorMap(one, col, cv::COLORMAP_TURBO);
    CHECK(col.at<cv::Vec3b>(0, 0) != cv::Vec3b(255, 255, 255));
    CHECK(col.at<cv::Vec3b>(0, 0) != cv::Vec3b(128, 128, 128));
  }
  CHECK(sm::tools::data_range(cv::Mat(2, 2, CV_32F, cv::Scalar(-1))).hi == 1.0);

  const cv::Mat bar = sm::tools::colour_bar(r, 240), bar_z = sm::tools::colour_bar(r, 240, &kCam);
  CHECK(bar.rows == 240);
  CHECK(bar_z.cols > bar.cols);  // room for the depth ticks
  const cv::Mat pic = sm::tools::disparity_picture(d, r, &kCam);
  CHECK(pic.rows == d.rows);
  CHECK(pic.cols > d.cols);

  cv::Mat gt(2, 2, CV_32F, cv::Scalar(10)), est = (cv::Mat_<float>(2, 2) << 10.5f, 13.f, -1.f, 10.f);
  gt.at<float>(1, 1) = 0;  // unknown
  const cv::Mat em = sm::tools::error_map(est, gt, cv::Mat());
  CHECK(em.at<cv::Vec3b>(0, 0) == cv::Vec3b(0, 160, 0));
  CHECK(em.at<cv::Vec3b>(0, 1) == cv::Vec3b(0, 0, 255));
  CHECK(em.at<cv::Vec3b>(1, 0) == cv::Vec3b(255, 0, 255));
  CHECK(em.at<cv::Vec3b>(1, 1) == cv::Vec3b(40, 40, 40));
  const cv::Mat big_est(120, 160, CV_32F, cv::Scalar(5)), big_gt(120, 160, CV_32F, cv::Scalar(5));
  const cv::Mat ep = sm::tools::error_map_picture(big_est, big_gt, cv::Mat());
  CHECK(ep.cols == 160);
  REQUIRE(ep.rows > 120);
  // the legend strip shows the four class colours
  const cv::Mat strip = ep.rowRange(120, ep.rows);
  for (const cv::Scalar& k :
       {sm::tools::kGoodColour, sm::tools::kBadColour, sm::tools::kNoEstColour, sm::tools::kNotScoredColour}) {
    cv::Mat hit;
    cv::inRange(strip, k, k, hit);
    CHECK(cv::countNonZero(hit) > 4);
  }

  const cv::Mat base(120, 160, CV_8UC3, cv::Scalar(0, 128, 0));
  sm::Object o;
  o.x0 = 20;
  o.y0 = 30;
  o.x1 = 80;
  o.y1 = 90;
  const cv::Mat plain = sm::tools::draw_objects(base, {o}, false, false);
  const cv::Mat flagged = sm::tools::draw_objects(base, {o}, true, true);
  // for a look: <build>/tests/depth_tmp/pictures_unit/
  const fs::path look = sm::test::fresh_dir(tmp_root() / "pictures_unit");
  cv::imwrite((look / "objects_flagged.png").string(), flagged);
  cv::imwrite((look / "disparity_picture.png").string(), pic);
  CHECK(plain.at<cv::Vec3b>(60, 20) == cv::Vec3b(255, 255, 255));  // box edge
  cv::Mat label_area;
  cv::inRange(plain(cv::Rect(21, 31, 20, 12)), cv::Scalar(150, 150, 150), cv::Scalar(255, 255, 255), label_area);
  CHECK(cv::countNonZero(label_area) > 3);  // "#0"
  CHECK(plain.at<cv::Vec3b>(118, 2) == cv::Vec3b(0, 128, 0));
  CHECK(flagged.at<cv::Vec3b>(118, 1) != cv::Vec3b(0, 128, 0));  // the flags' box

  const cv::Mat row = sm::tools::side_by_side({ep, cv::Mat(120, 50, CV_8UC1, cv::Scalar(9))});
  CHECK(row.size() == cv::Size(210, ep.rows));
  CHECK(row.at<cv::Vec3b>(119, 200) == cv::Vec3b(9, 9, 9));
  CHECK(row.at<cv::Vec3b>(ep.rows - 1, 200) == cv::Vec3b(0, 0, 0));  // padding

  // cloud view: a point straight ahead at z_max/2 lands at the centre column, half way up
  const cv::Mat view = sm::tools::cloud_view({{0.f, 0.f, 2.f, 200}}, {200, 220}, 4.0);
  CHECK(view.at<cv::Vec3b>(210 - 100, 100) == cv::Vec3b(200, 200, 200));
}

TEST_CASE("temporaries are removed on SIGINT / SIGTERM, the process ends with the signal", "[unit][cleanup]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "signals");
  for (int sig : {SIGINT, SIGTERM}) {
    const fs::path out = dir / fmt::format("sig{}", sig);
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      signal(SIGINT, SIG_DFL);  // not Catch2's handlers: the tools' own situation
      signal(SIGTERM, SIG_DFL);
      sm::tools::OutputSet outs;
      std::ofstream((outs.stage((out / "new" / "a.json").string(), true))) << "{}";
      std::ofstream(outs.stage((dir / "b.txt").string())) << "b";
      const sm::tools::RemoveOnSignal vcd((dir / "top.part.vcd").string());
      std::ofstream((dir / "top.part.vcd").string()) << "$end";
      raise(sig);
      _exit(3);  // not reached
    }
    int st = 0;
    REQUIRE(waitpid(pid, &st, 0) == pid);
    CHECK(WIFSIGNALED(st));
    CHECK(WTERMSIG(st) == sig);
    INFO("left: " << fmt::format("{}", fmt::join(listing(dir), " ")));
    CHECK(listing(dir).empty());
  }
}

TEST_CASE("stereo_model depth of a synthetic scene: median error below 1 % of the true depth", "[system][depth]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "scene_depth");
  const fs::path scene = dir / "scene";
  // slanted background (disparity 40..62) and five objects (up to ~120): true depths
  // 0.5..1.5 m at f 500 px, B 0.12 m; every disparity sub-pixel on the background
  auto r = run(SM_SCENE_EXE, fmt::format("--out {} --focal-px 500 --baseline-m 0.12 --bg-disp 40 --bg-slant-x 10 "
                                         "--bg-slant-y 12 --seed 3",
                                         scene.string()));
  REQUIRE(r.rc == 0);
  const std::string model = fmt::format("{0}/left.png {0}/right.png --calib {0}/calib.json ", scene.string());
  r = run(SM_STEREO_MODEL_EXE, model + fmt::format("--disp-file {0}/d.pfm --depth-file {0}/z.pfm --cloud {0}/c.ply "
                                                   "--cloud-view {0}/view.png",
                                                   dir.string()));
  INFO(r.err);
  REQUIRE(r.rc == 0);
  const sm::tools::Scene s = sm::tools::load_scene(scene.string());
  const cv::Mat z = sm::tools::read_depth_file((dir / "z.pfm").string());
  const cv::Mat disp = sm::tools::read_disparity_file((dir / "d.pfm").string());
  const double fb = 500 * 0.12;
  std::vector<double> rel;
  long valid = 0;
  for (int y = 0; y < z.rows; ++y)
    for (int x = 0; x < z.cols; ++x) {
      const float zz = z.at<float>(y, x), d = disp.at<float>(y, x);
      CHECK(std::isfinite(zz) == (d > 0));  // depth exactly where the disparity is positive
      if (!std::isfinite(zz)) continue;
      ++valid;
      const double truth = fb / s.gt.at<float>(y, x);  // the scene's own geometry (gt.png, 1/256 px)
      rel.push_back(std::fabs(zz - truth) / truth);
    }
  REQUIRE(valid > static_cast<long>(z.total() * 9 / 10));
  std::nth_element(rel.begin(), rel.begin() + static_cast<long>(rel.size() / 2), rel.end());
  const double median = rel[rel.size() / 2];
  std::printf("depth of %ld valid pixels: median |Z - Z_true| / Z_true = %.3f %%\n", valid, 100 * median);
  CHECK(median < 0.01);
  // the cloud holds every valid pixel; a depth cut leaves the far ones out
  const std::string ply = sm::test::slurp(dir / "c.ply");
  CHECK(ply.find(fmt::format("element vertex {}\n", valid)) != std::string::npos);
  long near = 0;
  for (auto it = z.begin<float>(); it != z.end<float>(); ++it) near += *it <= 1.0f;
  REQUIRE(run(SM_STEREO_MODEL_EXE, model + fmt::format("--cloud {}/near.ply --cloud-max-depth 1", dir.string())).rc ==
          0);
  CHECK(sm::test::slurp(dir / "near.ply").find(fmt::format("element vertex {}\n", near)) != std::string::npos);
  CHECK(near > 0);
  CHECK(near < valid);
  const cv::Mat view = cv::imread((dir / "view.png").string());
  CHECK(view.size() == z.size());
}

TEST_CASE("stereo_model --colour and sm_evaluate --disp-images draw colour bars and legends", "[unit][pictures]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "pictures");
  const fs::path scene = dir / "data" / "small";
  REQUIRE(run(SM_SCENE_EXE, fmt::format("--out {} --width 64 --height 48 --levels 16 --seed 2 --objects 3 "
                                        "--focal-px 80 --baseline-m 0.1",
                                        scene.string()))
              .rc == 0);
  const std::string pair = fmt::format("{0}/left.png {0}/right.png --disp 16 ", scene.string());
  REQUIRE(run(SM_STEREO_MODEL_EXE, pair + "--colour " + (dir / "plain.png").string()).rc == 0);
  REQUIRE(run(SM_STEREO_MODEL_EXE,
              pair + "--calib " + scene.string() + "/calib.json --colour " + (dir / "depth.png").string())
              .rc == 0);
  const cv::Mat plain = cv::imread((dir / "plain.png").string()), depth = cv::imread((dir / "depth.png").string());
  CHECK(plain.rows == 48);
  CHECK(plain.cols > 64);          // the colour bar
  CHECK(depth.cols > plain.cols);  // and its depth ticks
  const auto r = run(SM_EVALUATE_EXE, fmt::format("{} --levels 16 --methods model,bm -q --disp-images {}",
                                                  (dir / "data").string(), (dir / "imgs").string()));
  INFO(r.err);
  REQUIRE(r.rc == 0);
  for (const char* f : {"small_gt.png", "small_model.png", "small_model_errors.png", "small_bm_errors.png"}) {
    const cv::Mat m = cv::imread((dir / "imgs" / f).string());
    INFO(f);
    CHECK(m.type() == CV_8UC3);
    CHECK(m.rows >= 48);
  }
  CHECK(cv::imread((dir / "imgs" / "small_model_errors.png").string()).rows > 48);  // the legend
}

TEST_CASE("stereo_model: depth outputs and calibration files checked before any work", "[robust][depth]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "model_robust");
  const fs::path scene = dir / "scene", out = sm::test::fresh_dir(dir / "out");
  REQUIRE(
      run(SM_SCENE_EXE, fmt::format("--out {} --width 64 --height 48 --levels 16 --seed 2 --objects 3", scene.string()))
          .rc == 0);
  REQUIRE(run(SM_SCENE_EXE, fmt::format("--out {}_cam --width 64 --height 48 --levels 16 --seed 2 --objects 3 "
                                        "--focal-px 80 --baseline-m 0.1",
                                        scene.string()))
              .rc == 0);
  const std::string pair = fmt::format("{0}/left.png {0}/right.png --disp 16 ", scene.string());
  const std::string calib = scene.string() + "/calib.json", calib_cam = scene.string() + "_cam/calib.json";
  const std::string o = (out / "z.pfm").string(), c = (out / "c.ply").string();
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--depth-file " + o), "stereo_model", "need --calib with a camera");
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--cloud " + c + " --calib " + calib), "stereo_model", "no 'camera'");
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--depth-file " + (out / "z.tif").string() + " --calib " + calib_cam),
               "stereo_model", "must end in .pfm or .png");
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--cloud " + (out / "c.txt").string() + " --calib " + calib_cam),
               "stereo_model", "must end in .ply");
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--cloud " + c + " --cloud-max-depth nan --calib " + calib_cam),
               "stereo_model", "--cloud-max-depth nan");
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--cloud " + c + " --depth-file " + (out / "nodir" / "z.pfm").string() +
                                            " --calib " + calib_cam),
               "stereo_model", "z.pfm");
  // calibration files: an unknown key, a radius above the IP's RECT_RADIUS
  nlohmann::json j;
  std::ifstream(calib_cam) >> j;
  const std::string bad = (dir / "bad.json").string();
  nlohmann::json k = j;
  k["grid_bank"] = 1;
  std::ofstream(bad) << k.dump();
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--disp-file " + o + " --calib " + bad), "stereo_model",
               "unknown key 'grid_bank'");
  k = j;
  k["rect_radius_needed"] = 50;
  std::ofstream(bad) << k.dump();
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--disp-file " + o + " --calib " + bad), "stereo_model",
               "'rect_radius_needed' = 50 exceeds the IP's RECT_RADIUS 18");
  CHECK(listing(out).empty());
  // a radius the IP holds is fine
  k["rect_radius_needed"] = 25;
  std::ofstream(bad) << k.dump();
  expect_error(run(SM_STEREO_MODEL_EXE, pair + "--depth-file " + o + " --calib " + bad), "stereo_model",
               "'rect_radius_needed' = 25 exceeds the IP's RECT_RADIUS 18");
  CHECK(run(SM_STEREO_MODEL_EXE, pair + "--rect-radius 25 --depth-file " + o + " --calib " + bad).rc == 0);
  CHECK(listing(out) == std::vector<std::string>{"z.pfm"});
  // sm_ref_frames (the cocotb bench's reference) holds a calibration to its RECT_RADIUS too
  const nlohmann::json regs = {{"max_width", 64}, {"max_height", 48}, {"disp", 16},  {"census", 7},
                               {"sw", 3},         {"rect_radius", 4}, {"calib", bad}};
  const std::string regs_path = (dir / "ref_regs.json").string(), ref = (out / "ref.json").string();
  std::ofstream(regs_path) << regs.dump();
  expect_error(run(SM_REF_FRAMES_EXE,
                   fmt::format("--regs {0} -o {1} {2}/left.png {2}/right.png", regs_path, ref, scene.string())),
               "sm_ref_frames", "'rect_radius_needed' = 25 exceeds the IP's RECT_RADIUS 4");
  CHECK(listing(out) == std::vector<std::string>{"z.pfm"});
}

namespace {

// sm_calibrate on the synthetic rig: the rig's boards written once per run of the test.
fs::path rig_dir() {
  static const fs::path d = [] {
    const fs::path p = sm::test::fresh_dir(tmp_root() / "rig");
    sm::test::write_chessboard_rig(p);
    return p;
  }();
  return d;
}

}  // namespace

TEST_CASE("sm_calibrate writes the rectified camera in the unit of --square", "[unit][depth]") {
  const fs::path out = sm::test::fresh_dir(tmp_root() / "calib_camera");
  // the rig's right camera sits 2 squares to the right, f 600 px at 640x480
  const auto r = run(SM_CALIBRATE_EXE, fmt::format("{} --square 0.03 -o {}/c.json --yaml {}/c.yaml", rig_dir().string(),
                                                   out.string(), out.string()));
  INFO(r.out << r.err);
  REQUIRE(r.rc == 0);
  const sm::CalibFile c = sm::load_calib((out / "c.json").string());
  REQUIRE(c.camera.has_value());
  CHECK(c.camera->baseline_m == Approx(0.06).epsilon(0.02));
  CHECK(c.camera->f_px == Approx(300).epsilon(0.1));  // at 320x240; alpha 0 zooms a little
  CHECK(c.camera->cx == Approx(159.5).margin(20));
  CHECK(c.camera->cy == Approx(119.5).margin(20));
  CHECK(r.out.find("baseline 0.06") != std::string::npos);
}

TEST_CASE("sm_calibrate refuses bad options and list entries up front, leaves nothing", "[robust][calibrate]") {
  const fs::path out = sm::test::fresh_dir(tmp_root() / "calib_robust");
  const std::string o = fmt::format(" -o {0}/c.json --yaml {0}/c.yaml", out.string());
  const std::string rig = rig_dir().string();
  using Clock = std::chrono::steady_clock;
  for (const auto& [args, what] :
       std::vector<std::pair<std::string, std::string>>{{"--alpha 5", "--alpha 5: outside 0..1"},
                                                        {"--alpha nan", "--alpha nan: outside 0..1"},
                                                        {"--alpha -1", "--alpha -1: outside 0..1"},
                                                        {"--square inf", "--square inf: must be finite"},
                                                        {"--square 0", "--square 0: must be finite"},
                                                        {"--check-vdisp nan", "--check-vdisp nan"},
                                                        {"--rect-radius 60", "--rect-radius 60 outside 1..31"}}) {
    const auto t0 = Clock::now();
    const auto r = run(SM_CALIBRATE_EXE, rig + " " + args + o);
    expect_error(r, "sm_calibrate", what);
    CHECK(r.rc == 2);  // a command-line value, as the parser's own range checks
    // before calibrating: far less than the ~1 s the rig's calibration takes
    CHECK(std::chrono::duration<double>(Clock::now() - t0).count() < 0.5);
  }
  // a list naming a missing image: one clean line, no OpenCV "[ WARN:" chatter
  const fs::path list = out.parent_path() / "calib_list.txt";
  std::ofstream(list) << rig << "/left00.png\n"
                      << rig << "/right00.png\n"
                      << rig << "/left99.png\n"
                      << rig << "/right01.png\n";
  const auto r = run(SM_CALIBRATE_EXE, list.string() + o);
  expect_error(r, "sm_calibrate", "entry 3");
  CHECK(r.err.find("left99.png': no such file") != std::string::npos);
  CHECK(r.out.find("WARN") == std::string::npos);
  CHECK(listing(out).empty());
}

TEST_CASE("sm_calibrate interrupted by SIGINT / SIGTERM leaves no temporary", "[robust][calibrate]") {
  const fs::path out = sm::test::fresh_dir(tmp_root() / "calib_signal");
  const std::string rig = rig_dir().string();
  for (int sig : {SIGINT, SIGTERM}) {
    // stop it while its outputs exist only as temporaries (after the calibration, during
    // the check that writes the rectified pairs)
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      const int nul = open("/dev/null", O_WRONLY);
      dup2(nul, 1);
      const std::string o = (out / "c.json").string(), y = (out / "c.yaml").string(), rect = (out / "rect").string();
      execl(SM_CALIBRATE_EXE, SM_CALIBRATE_EXE, rig.c_str(), "-o", o.c_str(), "--yaml", y.c_str(), "--save-rectified",
            rect.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    bool seen = false;
    int st = 0;
    for (int i = 0; i < 20000 && !seen; ++i) {
      // a staged output; not the probe of the up-front output check (also removed on a signal)
      for (const auto& n : listing(out)) seen = seen || (n[0] == '.' && n.rfind(".sm_probe", 0) != 0);
      if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
      if (waitpid(pid, &st, WNOHANG) == pid) FAIL("sm_calibrate ended before a temporary was seen");
    }
    REQUIRE(seen);
    kill(pid, sig);
    REQUIRE(waitpid(pid, &st, 0) == pid);
    CHECK(WIFSIGNALED(st));
    if (WIFSIGNALED(st)) CHECK(WTERMSIG(st) == sig);
    INFO("left: " << fmt::format("{}", fmt::join(listing(out), " ")));
    CHECK(listing(out).empty());
  }
}

TEST_CASE("sm_evaluate rectifies a raw scene with its calib.json: a rotated scene scores as a rectified one",
          "[unit][evaluate]") {
  const fs::path dir = sm::test::fresh_dir(tmp_root() / "evaluate_calib");
  const fs::path scene = dir / "data" / "rot";
  REQUIRE(run(SM_SCENE_EXE, fmt::format("--out {} --width 96 --height 64 --levels 32 --seed 3 --objects 3 "
                                        "--rot-deg 1.5 --vshift 1.5",
                                        scene.string()))
              .rc == 0);
  auto bad = [&](const std::string& name) {
    const fs::path js = dir / (name + ".json");
    const auto r = run(SM_EVALUATE_EXE, fmt::format("{} --levels 32 --methods model -q --json {}",
                                                    (dir / "data").string(), js.string()));
    INFO(r.err);
    REQUIRE(r.rc == 0);
    return nlohmann::json::parse(sm::test::slurp(js)).at("scenes").at(0);
  };
  const nlohmann::json with = bad("with");
  CHECK(with.at("calib") == (scene / "calib.json").string());
  fs::remove(scene / "calib.json");
  const nlohmann::json without = bad("without");
  CHECK(without.at("calib").is_null());
  const double b_with = with.at("methods").at("model").at("bad1_pct");
  const double b_without = without.at("methods").at("model").at("bad1_pct");
  INFO(b_with << " % with the scene's calib.json, " << b_without << " % without");
  CHECK(b_with < b_without / 2);
}
