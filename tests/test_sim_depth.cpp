// stereo_sim's metric outputs, pictures, waves, defaults and help (issue 42), on the small
// configuration: depth and point cloud of a synthetic scene with a known camera against
// the scene's own geometry, a scene folder's calib.json used (a rotated scene) or its
// absence reported, the 8-bit preview's invalid code, the panel's calibrated rows, the
// wave file's time stamps in the core clock's real period, progress lines within a run,
// the built-in scene of the configuration's own size, and every register option's range
// in --help.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "sm_cmd.hpp"
#include "sm_sim_run.hpp"
#include "sm_test_util.hpp"
#include "toolio/sm_depth.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_scenegen.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kTmp = fs::path(SM_TEST_TMP);

sm::test::SimRun sim(const std::string& name, const std::string& args) {
  return sm::test::run_sim(SM_STEREO_SIM_SMALL, kTmp, name, args + " --frames 1");
}

// A 64x48 scene of 16 levels with a camera (f 80 px, B 0.1 m): a fronto-parallel
// background at disparity 6 (1.33 m) and three objects; `rot` rotates the right camera.
fs::path camera_scene(const std::string& name, double rot = 0, bool camera = true) {
  sm::tools::SceneParams p = sm::test::scene_params(64, 48, 16, 2, 3);
  p.bg_disp = 6;
  p.bg_slant_x = 0;
  p.bg_slant_y = 0;
  p.rot_deg = rot;
  p.vshift = rot;
  if (camera) {
    p.focal_px = 80;
    p.baseline_m = 0.1;
  }
  const fs::path dir = kTmp / name;
  fs::remove_all(dir);
  sm::tools::write_scene(sm::tools::render_scene(p), p, dir.string());
  return dir;
}

std::string scene_arg(const fs::path& s) { return "--scene \"" + s.string() + "\""; }

}  // namespace

// The depth is f * B / d of the output disparity, and the median disparity error is at most
// one step of the output's 1/16 px: the scene's background is 6 levels away, where one step
// is 1.04 % of the depth (the census-only cost had the median pixel exact, the cost with the
// intensity term has it one step off, at less than half the mean error: docs/evaluation.md,
// "Intensity term in the matching cost").
TEST_CASE("stereo_sim depth and cloud of a scene with a camera: depth f B / d, median error one 1/16 px step",
          "[sim][depth]") {
  const fs::path scene = camera_scene("cam_scene");
  const fs::path z_file = kTmp / "cam_z.pfm", ply = kTmp / "cam.ply";
  const auto r = sim(
      "cam_run", scene_arg(scene) + fmt::format(" --depth-file \"{}\" --cloud \"{}\"", z_file.string(), ply.string()));
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.report.at("calibration").at("from_scene") == true);
  CHECK(r.report.at("calibration").at("camera").at("f_px") == 80.0);
  const sm::tools::Scene s = sm::tools::load_scene(scene.string());
  const cv::Mat z = sm::tools::read_depth_file(z_file.string());
  const cv::Mat disp = sm::tools::read_disparity_file((r.dir / "disparity.pfm").string());
  REQUIRE(z.size() == s.gt.size());
  std::vector<double> rel, err;
  int off_formula = 0;
  for (int y = 0; y < z.rows; ++y)
    for (int x = 0; x < z.cols; ++x) {
      const float zz = z.at<float>(y, x), d = disp.at<float>(y, x);
      CHECK(std::isfinite(zz) == (d > 0));  // depth exactly where the disparity is positive
      if (!std::isfinite(zz)) continue;
      off_formula += std::fabs(zz - 80 * 0.1 / d) > 1e-5 * zz;
      const double truth = 80 * 0.1 / s.gt.at<float>(y, x);  // the scene's geometry
      rel.push_back(std::fabs(zz - truth) / truth);
      err.push_back(std::fabs(d - s.gt.at<float>(y, x)));
    }
  CHECK(off_formula == 0);
  REQUIRE(rel.size() > z.total() / 2);
  std::nth_element(rel.begin(), rel.begin() + static_cast<long>(rel.size() / 2), rel.end());
  std::nth_element(err.begin(), err.begin() + static_cast<long>(err.size() / 2), err.end());
  INFO("median relative depth error " << rel[rel.size() / 2] << ", median disparity error " << err[err.size() / 2]);
  CHECK(err[err.size() / 2] <= 1.0 / 16 + 1e-6);
  CHECK(rel[rel.size() / 2] < 0.011);
  // the cloud: one vertex per finite depth
  CHECK(sm::test::slurp(ply).find(fmt::format("element vertex {}\n", rel.size())) != std::string::npos);
  // the panel has the point-cloud row under the error-map row
  const cv::Mat panel = cv::imread((r.dir / "panel.png").string());
  const auto plain = sim("cam_plain", scene_arg(scene) + " --calib \"" + (kTmp / "none.json").string() + "\"");
  CHECK(plain.rc == 2);  // a missing --calib is an error, not ignored
  fs::remove(scene / "calib.json");
  const auto nocal = sim("cam_nocal", scene_arg(scene));
  REQUIRE(nocal.rc == 0);
  CHECK(nocal.report.at("calibration").at("file").is_null());
  CHECK(nocal.out.find("the scene has no calib.json") != std::string::npos);
  const cv::Mat panel0 = cv::imread((nocal.dir / "panel.png").string());
  CHECK(panel.rows > panel0.rows);
}

TEST_CASE("stereo_sim depth options: one error line without a camera, nothing written", "[sim][depth]") {
  const fs::path scene = camera_scene("nocam_scene", 0, false);
  for (const char* opt : {"--depth-file z.pfm", "--cloud c.ply", "--cloud-view v.png"}) {
    INFO(opt);
    const auto r = sim("nocam_run", scene_arg(scene) + " " + opt);
    CHECK(r.rc == 2);
    CHECK(r.err.find("camera") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!fs::exists(r.dir));
  }
  const auto bad = sim("nocam_ext", scene_arg(camera_scene("cam2")) + " --depth-file z.txt");
  CHECK(bad.rc == 2);
  CHECK(bad.err.find(".pfm or .png") != std::string::npos);
}

TEST_CASE("stereo_sim uses a rotated scene's calib.json: far fewer bad pixels than without", "[sim][depth]") {
  const fs::path scene = camera_scene("rot_scene", 1.5);
  const auto with = sim("rot_with", scene_arg(scene));
  REQUIRE(with.rc == 0);
  CHECK(with.report.at("calibration").at("from_scene") == true);
  fs::remove(scene / "calib.json");
  const auto without = sim("rot_without", scene_arg(scene));
  REQUIRE(without.rc == 0);
  const double b_with = with.report.at("bad1_percent"), b_without = without.report.at("bad1_percent");
  INFO(b_with << " % with, " << b_without << " % without");
  CHECK(b_with < b_without / 2);
}

TEST_CASE("stereo_sim pictures: the 8-bit preview tells disparity 0 from invalid", "[sim][pictures]") {
  const auto r = sim("preview", "");
  REQUIRE(r.rc == 0);
  const cv::Mat disp = sm::tools::read_disparity_file((r.dir / "disparity.pfm").string());
  const cv::Mat g = cv::imread((r.dir / "disparity.png").string(), cv::IMREAD_UNCHANGED);
  REQUIRE(g.type() == CV_8UC1);
  REQUIRE(g.size() == disp.size());
  const int levels = r.report.at("config").at("disp");
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.cols; ++x) {
      const float d = disp.at<float>(y, x);
      const int want = d < 0 ? 0 : 1 + static_cast<int>(std::lround(d * 254.0 / (levels - 1)));
      REQUIRE(g.at<uint8_t>(y, x) == want);
    }
  // the colour picture has its colour bar on the right
  CHECK(cv::imread((r.dir / "disparity_color.png").string()).cols > disp.cols);
}

TEST_CASE("stereo_sim waves: time stamps in picoseconds at the core clock's period", "[sim][waves]") {
  for (const double mhz : {100.0, 40.0}) {
    const fs::path vcd = kTmp / fmt::format("period_{}.vcd", mhz);
    const auto r = sim("period", fmt::format("--core-mhz {} --wave \"{}\" --vcd-lines 1", mhz, vcd.string()));
    INFO(r.err);
    REQUIRE(r.rc == 0);
    std::ifstream in(vcd);
    std::string ts;
    std::vector<uint64_t> stamps;
    bool body = false;  // after $enddefinitions: a line "#<time>" is a time stamp
    for (std::string l; std::getline(in, l);) {
      if (l.rfind("$timescale", 0) == 0) ts = l;
      if (l.find("$enddefinitions") != std::string::npos) body = true;
      if (body && !l.empty() && l[0] == '#') stamps.push_back(std::stoull(l.substr(1)));
    }
    CHECK(ts == "$timescale 1ps $end");
    REQUIRE(stamps.size() > 10);
    const uint64_t period = static_cast<uint64_t>(std::llround(1e6 / mhz));  // ps
    // both edges of every clock: a falling half, then the rising edge half a period later
    for (size_t i = 1; i < stamps.size(); ++i) REQUIRE(stamps[i] - stamps[i - 1] == period / 2);
    CHECK(stamps[0] % period == 0);
  }
}

TEST_CASE("stereo_sim progress within a run: plain lines in a log, none with -q", "[sim][progress]") {
  fs::create_directories(kTmp);
  // ~5 s or more of simulation: past the first progress line's 3 s
  const std::string args = fmt::format("--frames 1000 --continuous --no-check --out \"{}\"", (kTmp / "prog").string());
  const auto r = sm::test::run_cmd(SM_STEREO_SIM_SMALL, args, kTmp);
  REQUIRE(r.rc == 0);
  const std::regex line(R"(stereo_sim: frame \d+/1000 row \d+/48: [0-9.]+ rows/s, \d+ s left)");
  CHECK(std::regex_search(r.err, line));
  CHECK(r.err.find('\r') == std::string::npos);  // not a terminal: no line rewritten in place
  const auto q = sm::test::run_cmd(SM_STEREO_SIM_SMALL, args + " -q", kTmp);
  REQUIRE(q.rc == 0);
  CHECK(q.err.empty());
}

TEST_CASE("stereo_sim_small's built-in scene is of its own size and disparity range", "[sim][defaults]") {
  const auto r = sim("default_scene", "");
  REQUIRE(r.rc == 0);
  CHECK(r.report.at("input") == SM_SCENE_SMALL_DIR);
  CHECK(r.report.at("ground_truth").at("resized") == false);
  const sm::tools::Scene s = sm::tools::load_scene(SM_SCENE_SMALL_DIR);
  double lo = 0, hi = 0;
  cv::minMaxLoc(s.gt, &lo, &hi);
  CHECK(hi < r.report.at("config").at("disp").get<int>());
}

TEST_CASE("stereo_sim --help shows every register option's range", "[sim][help]") {
  fs::create_directories(kTmp);
  const auto h = sm::test::run_cmd(SM_STEREO_SIM_SMALL, "--help", kTmp);
  REQUIRE(h.rc == 0);
  // each register option: "  --name INT:INT in lo..hi=default" on its line, "(register NAME)" in its help
  std::istringstream in(h.out);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  int regs = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find("(register ") == std::string::npos) continue;
    ++regs;
    const std::string opt = lines[i].find("  --") == 0 ? lines[i] : lines[i - 1];
    INFO(opt);
    CHECK(std::regex_search(opt, std::regex(R"(INT in -?\d+\.\.\d+)")));
  }
  CHECK(regs >= 10);
  CHECK(h.out.find("--occ INT:INT in 0..255") != std::string::npos);
}
