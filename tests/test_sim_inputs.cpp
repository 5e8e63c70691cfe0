// stereo_sim's input modes other than the built-in scene (--left/--right, --sequence,
// --video), on the small configuration: each run checks every output pixel of the RTL
// against the model itself, so these tests check what only the input side can get
// wrong: which pair goes into which frame (the last frame's disparity must equal a run
// of that pair alone), the video's left/right halves, and the errors on bad inputs.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "toolio/sm_scenegen.hpp"
#include "sm_cmd.hpp"
#include "sm_sim_run.hpp"
#include "sm_test_util.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kTmp = fs::path(SM_TEST_TMP);

using sm::test::slurp;

struct Run : sm::test::SimRun {
  cv::Mat disparity;  // the last frame's disparity.png as written
};

// stereo_sim_small <args> --continuous -q --out <tmp>/<name>: exit code, stderr, report,
// last disparity
Run sim(const std::string& name, const std::string& args) {
  Run r{sm::test::run_sim(SM_STEREO_SIM_SMALL, kTmp, name, args + " --continuous"), {}};
  if (fs::exists(r.dir / "disparity.png"))
    r.disparity = cv::imread((r.dir / "disparity.png").string(), cv::IMREAD_UNCHANGED);
  return r;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return !a.empty() && a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

void expect_ok(const Run& r, int frames) {
  INFO("stderr: " << r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.report.at("bit_exact") == true);
  CHECK(r.report.at("frames") == frames);
  CHECK(r.report.at("framing_ok") == true);
  REQUIRE(!r.disparity.empty());
}

void expect_error(const Run& r, const std::string& what) {
  INFO("stderr: " << r.err);
  CHECK(r.rc != 0);
  CHECK(r.err.find(what) != std::string::npos);
  CHECK(r.report.is_null());
}

// Two different 64x48 pairs (16 levels), written as PNG.
struct Pairs {
  cv::Mat l[2], r[2];
  fs::path lp[2], rp[2];
  Pairs() {
    fs::create_directories(kTmp);
    for (int i = 0; i < 2; ++i) {
      const sm::tools::SceneParams p = sm::test::scene_params(64, 48, 16, 11 + 7 * static_cast<unsigned>(i), 2 + i);
      const sm::tools::SyntheticScene s = sm::tools::render_scene(p);
      l[i] = s.left;
      r[i] = s.right;
      lp[i] = kTmp / ("pair" + std::to_string(i) + "_left.png");
      rp[i] = kTmp / ("pair" + std::to_string(i) + "_right.png");
      cv::imwrite(lp[i].string(), l[i]);
      cv::imwrite(rp[i].string(), r[i]);
    }
  }
  std::string args(int i) const { return "--left \"" + lp[i].string() + "\" --right \"" + rp[i].string() + "\""; }
};

}  // namespace

TEST_CASE("--left/--right: the pair repeated, and two different pairs give different outputs", "[sim][inputs]") {
  const Pairs p;
  const Run a = sim("pair0", p.args(0) + " --frames 2"), b = sim("pair1", p.args(1) + " --frames 2");
  expect_ok(a, 2);
  expect_ok(b, 2);
  // Without this, the comparisons below could not tell one pair from the other.
  CHECK(!same(a.disparity, b.disparity));
}

TEST_CASE("--sequence: pairs sorted by name, one per frame", "[sim][inputs]") {
  const Pairs p;
  const fs::path seq = kTmp / "seq";
  fs::remove_all(seq);
  fs::create_directories(seq);
  // Names chosen so that the sorted order is pair 0, pair 1 (and not creation order).
  fs::copy_file(p.lp[1], seq / "left_b.png");
  fs::copy_file(p.rp[1], seq / "right_b.png");
  fs::copy_file(p.lp[0], seq / "left_a.png");
  fs::copy_file(p.rp[0], seq / "right_a.png");
  const Run s = sim("seq_run", "--sequence \"" + seq.string() + "\" --frames 2");
  expect_ok(s, 2);
  const Run last = sim("seq_pair1", p.args(1) + " --frames 1");
  expect_ok(last, 1);
  CHECK(same(s.disparity, last.disparity));
  // --frames 1 takes the first pair only.
  const Run first = sim("seq_first", "--sequence \"" + seq.string() + "\" --frames 1");
  expect_ok(first, 1);
  const Run pair0 = sim("seq_pair0", p.args(0) + " --frames 1");
  expect_ok(pair0, 1);
  CHECK(same(first.disparity, pair0.disparity));

  SECTION("unequal left/right counts are an error") {
    fs::remove(seq / "right_b.png");
    expect_error(sim("seq_bad", "--sequence \"" + seq.string() + "\""), "left* and");
  }
  SECTION("a missing folder is an error") {
    expect_error(sim("seq_missing", "--sequence \"" + (kTmp / "no_such_folder").string() + "\""), "no such folder");
  }
}

TEST_CASE("--video: side-by-side frames split into left and right halves", "[sim][inputs]") {
  const Pairs p;
  const fs::path vid = kTmp / "pairs.avi";
  fs::remove(vid);
  {
    // OpenCV's own MJPEG writer (always built in): lossy, so the reference below is the
    // decoded video, not the PNGs.
    cv::VideoWriter w(vid.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0, cv::Size(128, 48), true);
    REQUIRE(w.isOpened());
    for (int i = 0; i < 2; ++i) {
      cv::Mat sbs, bgr;
      cv::hconcat(p.l[i], p.r[i], sbs);
      cv::cvtColor(sbs, bgr, cv::COLOR_GRAY2BGR);
      w.write(bgr);
    }
  }
  // The last decoded frame's halves, as a --left/--right pair.
  cv::VideoCapture cap(vid.string());
  REQUIRE(cap.isOpened());
  cv::Mat f, g;
  int n = 0;
  while (cap.read(f)) {
    cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
    ++n;
  }
  REQUIRE(n == 2);
  const fs::path l = kTmp / "video_last_left.png", r = kTmp / "video_last_right.png";
  cv::imwrite(l.string(), g(cv::Rect(0, 0, 64, 48)));
  cv::imwrite(r.string(), g(cv::Rect(64, 0, 64, 48)));

  const Run v = sim("video_run", "--video \"" + vid.string() + "\" --frames 2");
  expect_ok(v, 2);
  const Run ref = sim("video_ref", "--left \"" + l.string() + "\" --right \"" + r.string() + "\" --frames 1");
  expect_ok(ref, 1);
  CHECK(same(v.disparity, ref.disparity));
  // Halves swapped must give another result, else the check above proves nothing.
  const Run swapped = sim("video_swapped", "--left \"" + r.string() + "\" --right \"" + l.string() + "\" --frames 1");
  expect_ok(swapped, 1);
  CHECK(!same(v.disparity, swapped.disparity));

  SECTION("an unreadable video is an error") {
    std::ofstream(kTmp / "broken.avi") << "not a video\n";
    expect_error(sim("video_bad", "--video \"" + (kTmp / "broken.avi").string() + "\""), "broken.avi");
  }
}
