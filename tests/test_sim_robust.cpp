// stereo_sim on bad input (issue 40, label robust): every class of bad option or file is
// refused before any work with one line "stereo_sim: error: ..." naming the option or
// file and the reason, exit code 2, and no output file (the out folder holds no
// report.json, picture or disparity file). Plus the run-time cases: the steady-state
// frame period, the budget verdict's exit code, Ctrl-C during a wave dump. Small
// configuration (stereo_sim_small; stereo_sim_small_fold where the core clock matters).
// One ctest per class: tests/sim_robust.cmake runs each [tag] on its own.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <thread>

#include "calib_file.hpp"
#include "toolio/sm_scenegen.hpp"
#include "sm_cmd.hpp"
#include "sm_sim_run.hpp"
#include "sm_test_util.hpp"

namespace fs = std::filesystem;

namespace {

// One folder per ctest (SM_ROBUST_CLASS): the classes run in parallel.
const fs::path kTmp = fs::path(SM_TEST_TMP) / (std::getenv("SM_ROBUST_CLASS") ? std::getenv("SM_ROBUST_CLASS") : "all");

std::string q(const fs::path& p) { return "\"" + p.string() + "\""; }

// stereo_sim_small <args> -q --out <tmp>/<name>
sm::test::SimRun sim(const std::string& name, const std::string& args, const std::string& exe = SM_STEREO_SIM_SMALL) {
  return sm::test::run_sim(exe, kTmp, name, args);
}

// Lines of `s` (without the empty last one).
std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> v;
  size_t b = 0;
  for (size_t e = s.find('\n'); e != std::string::npos; b = e + 1, e = s.find('\n', b)) v.push_back(s.substr(b, e - b));
  if (b < s.size()) v.push_back(s.substr(b));
  return v;
}

// Refused up front: exit 2, stderr exactly one line "stereo_sim: error: ..." holding
// every piece of `what`, no output in the run's folder nor at `extra` (when given).
void expect_refused(const sm::test::SimRun& r, const std::vector<std::string>& what, const fs::path& extra = {}) {
  INFO("stderr: " << r.err << "stdout: " << r.out);
  CHECK(r.rc == 2);
  const auto l = lines(r.err);
  REQUIRE(l.size() == 1);
  CHECK(l[0].rfind("stereo_sim: error: ", 0) == 0);
  for (const auto& w : what) CHECK(l[0].find(w) != std::string::npos);
  CHECK(r.out.empty());
  for (const char* f : {"report.json", "panel.png", "disparity.png", "disparity_color.png", "disparity.pfm"})
    CHECK_FALSE(fs::exists(r.dir / f));
  if (!extra.empty()) CHECK_FALSE(fs::exists(extra));
}

// A 64x48 scene folder: left.png, right.png and, with `gt`, gt.png (disparity x 4).
fs::path make_scene(const std::string& name, bool gt, bool scale) {
  const fs::path d = sm::test::fresh_dir(kTmp / name);
  const sm::tools::SyntheticScene s = sm::tools::render_scene(sm::test::scene_params(64, 48, 16, 5, 2));
  cv::imwrite((d / "left.png").string(), s.left);
  cv::imwrite((d / "right.png").string(), s.right);
  if (gt) {
    cv::Mat g;
    s.gt.convertTo(g, CV_16U, 4.0);
    cv::imwrite((d / "gt.png").string(), g);
  }
  if (scale) std::ofstream(d / "scale.txt") << "4 16\n";
  return d;
}

// A regular file where a folder is expected.
fs::path a_file() {
  fs::create_directories(kTmp);
  const fs::path f = kTmp / "a_file";
  std::ofstream(f) << "x\n";
  return f;
}

}  // namespace

TEST_CASE("--synth-json with a field of the wrong type: refused before the run, naming file and key", "[synth_json]") {
  fs::create_directories(kTmp);
  const fs::path bad = kTmp / "synth_total_string.json";
  std::ofstream(bad) << R"({"total": "12 LUTs"})"
                     << "\n";
  expect_refused(sim("synth_total", "--synth-json " + q(bad)), {bad.string(), "'total'", "string"});
  const fs::path bad2 = kTmp / "synth_luts_string.json";
  std::ofstream(bad2) << R"({"total": {"luts": "many"}})"
                      << "\n";
  expect_refused(sim("synth_luts", "--synth-json " + q(bad2)), {bad2.string(), "'total.luts'"});
  const fs::path bad3 = kTmp / "synth_not_json.json";
  std::ofstream(bad3) << "{\"total\": \n";
  expect_refused(sim("synth_not_json", "--synth-json " + q(bad3)), {bad3.string(), "not a synthesis report"});
  expect_refused(sim("synth_missing", "--synth-json " + q(kTmp / "no_such.json")), {"--synth-json", "no such file"});
}

TEST_CASE("--disp-file where no file can be created: refused before the run", "[disp_file]") {
  const fs::path f = a_file();
  expect_refused(sim("disp_unwritable", "--disp-file " + q(f / "sub" / "d.pfm")), {"--disp-file", "not a folder"});
  expect_refused(sim("disp_ext", "--disp-file " + q(kTmp / "d.tif")), {"--disp-file", ".pfm or .png"});
  // A missing folder is created, like --out's.
  const fs::path made = kTmp / "disp_made" / "sub" / "d.pfm";
  fs::remove_all(kTmp / "disp_made");
  const auto ok = sim("disp_made_run", "--frames 1 --disp-file " + q(made));
  INFO(ok.err);
  CHECK(ok.rc == 0);
  CHECK(fs::exists(made));
}

TEST_CASE("--vcd where no file can be created: refused before the run with the reason", "[wave_path]") {
  const fs::path f = a_file();
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = sim("wave_unwritable", "--vcd " + q(f / "x.vcd") + " --vcd-frame 3 --frames 4");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  expect_refused(r, {"--wave", (f / "x.vcd").string(), "not a folder"});
  CHECK_FALSE(fs::exists(f.parent_path() / "x.part.vcd"));
  CHECK(r.err.find("without tracing") == std::string::npos);
  CHECK(s < 30);  // refused, not simulated (a generous bound: the run itself takes well under a second here)
  expect_refused(sim("wave_proc", "--vcd /proc/x.vcd --vcd-frame 3 --frames 4"),
                 {"--wave /proc/x.vcd", "cannot write"});
}

TEST_CASE("--disp-file naming another output of the run: refused", "[name_clash]") {
  for (const char* name : {"panel.png", "disparity.png", "disparity_color.png"}) {
    const fs::path out = kTmp / "clash";
    fs::remove_all(out);
    const auto r = sm::test::run_sim(SM_STEREO_SIM_SMALL, kTmp, "clash", "--disp-file " + q(out / name));
    expect_refused(r, {"--disp-file", name, "same file as --out"});
  }
}

TEST_CASE("an output naming an input or another output: refused, the input intact", "[name_clash]") {
  const fs::path sc = make_scene("clash_scene", true, true);
  const auto size = fs::file_size(sc / "left.png");
  expect_refused(sim("clash_input", "--scene " + q(sc) + " --disp-file " + q(sc / "left.png")),
                 {"--disp-file", "same file as the input --scene", "left.png"});
  expect_refused(sim("clash_depth_input", "--scene " + q(sc) + " --depth-file " + q(sc / "gt.png")),
                 {"--depth-file", "same file as the input --scene", "gt.png"});
  CHECK(fs::file_size(sc / "left.png") == size);
  const fs::path out = kTmp / "clash_view";
  expect_refused(sim("clash_view", "--cloud-view " + q(out / "panel.png")), {"--cloud-view", "same file as --out"});
}

TEST_CASE("--merge-shards: shards of one run only, never into one of them", "[merge]") {
  const fs::path sc = make_scene("merge_scene", true, true);
  const std::string in = "--scene " + q(sc) + " --frames 4";
  REQUIRE(sim("shard_a", in + " --frame-range 0:2").rc == 0);
  REQUIRE(sim("shard_b", in + " --frame-range 2:4").rc == 0);
  REQUIRE(sim("shard_other", in + " --frame-range 2:4 --occ 30").rc == 0);  // another run's frames 2..3
  const fs::path a = kTmp / "shard_a", b = kTmp / "shard_b", other = kTmp / "shard_other";
  expect_refused(sim("merge_mixed", "--merge-shards " + q(a) + " " + q(other)),
                 {other.string(), "a shard of another run"});
  const auto into =
      sm::test::run_cmd(SM_STEREO_SIM_SMALL, "--merge-shards " + q(a) + " " + q(b) + " -q --out " + q(a), kTmp);
  CHECK(into.rc == 2);
  CHECK(into.err.find("one of the shard folders being merged") != std::string::npos);
  CHECK(fs::exists(a / "report.json"));
  const auto ok = sim("merge_ok", "--merge-shards " + q(a) + " " + q(b));
  INFO(ok.err);
  REQUIRE(ok.rc == 0);
  CHECK(ok.report["frames"] == 4);
  CHECK(ok.report["status_note"].get<std::string>().find("frames 2..3") != std::string::npos);
}

TEST_CASE("inputs that exclude each other, options that do not apply: refused", "[exclusive]") {
  const fs::path sc = make_scene("excl_scene", true, true);
  expect_refused(sim("excl_pair_scene", "--left a.png --right b.png --scene " + q(sc)), {"--left", "--scene"});
  expect_refused(sim("excl_seq_video", "--sequence X --video Y"), {"--sequence", "--video"});
  expect_refused(sim("excl_left_alone", "--left a.png"), {"--left", "--right"});
  expect_refused(sim("excl_blank", "--continuous --hblank 3"), {"--continuous", "--hblank"});
  expect_refused(sim("excl_vcd_frame", "--vcd-frame 2"), {"--vcd-frame", "--wave"});
}

TEST_CASE("numbers: finite, in range, and the real reason for a word", "[numbers]") {
  for (const char* o : {"--clock-mhz", "--pixel-clock", "--core-mhz"}) {
    expect_refused(sim("num_nan", std::string(o) + " nan"), {o, "nan", "not a finite number"});
    expect_refused(sim("num_inf", std::string(o) + " inf"), {o, "not a finite number"});
  }
  // the project's wording (sm::tools::int_in), as every tool's
  expect_refused(sim("num_word", "--frames abc"), {"--frames: 'abc': not an integer in 1..100000"});
  expect_refused(sim("num_range", "--frames 0"), {"--frames: 0: outside 1..100000"});
  expect_refused(sim("num_jobs", "--jobs 0"), {"--jobs: 0: outside 1..256"});
  expect_refused(sim("num_shards", "--list-shards 2x"), {"--list-shards: '2x': not an integer in 1..100000"});
  expect_refused(sim("num_clock", "--clock-mhz -5"), {"--clock-mhz", "outside"});
}

TEST_CASE("--scene: scale.txt goes with gt.png only; a missing folder is named", "[scene]") {
  expect_refused(sim("scene_missing", "--scene " + q(kTmp / "nonexist")), {"nonexist", "no such folder"});
  const fs::path gt_no_scale = make_scene("scene_gt_no_scale", true, false);
  expect_refused(sim("scene_gt_no_scale_run", "--scene " + q(gt_no_scale)), {"scale.txt", "no such file"});
  // Without ground truth: the run goes on, not scored.
  const fs::path bare = make_scene("scene_bare", false, false);
  const auto r = sim("scene_bare_run", "--frames 1 --scene " + q(bare));
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK_FALSE(r.report.contains("bad1_percent"));
  // With both: scored.
  const fs::path full = make_scene("scene_full", true, true);
  const auto s = sim("scene_full_run", "--frames 1 --scene " + q(full));
  REQUIRE(s.rc == 0);
  CHECK(s.report.contains("bad1_percent"));
}

TEST_CASE("--regs, --calib, --regs-at naming a folder or nothing: the path and the reason", "[input_files]") {
  fs::create_directories(kTmp);
  const std::string dir = kTmp.string();
  expect_refused(sim("dir_regs", "--regs " + q(dir)), {"--regs " + dir, "is a directory"});
  expect_refused(sim("dir_calib", "--calib " + q(dir)), {"--calib " + dir, "is a directory"});
  expect_refused(sim("dir_regs_at", "--frames 2 --regs-at 1=" + q(dir)), {"--regs-at " + dir, "is a directory"});
  const fs::path regs = kTmp / "regs_calib_dir.json";
  std::ofstream(regs) << nlohmann::json{{"calib", dir}}.dump() << "\n";
  expect_refused(sim("dir_regs_calib", "--regs " + q(regs)), {regs.string(), "'calib'", "is a directory"});
  expect_refused(sim("missing_left", "--left " + q(kTmp / "nope_l.png") + " --right " + q(kTmp / "nope_r.png")),
                 {"--left", "nope_l.png", "no such file"});
  // a sequence pair of two sizes, as --left/--right of two sizes
  const fs::path seq = sm::test::fresh_dir(kTmp / "seq_sizes");
  cv::imwrite((seq / "left1.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(90)));
  cv::imwrite((seq / "right1.png").string(), cv::Mat(20, 20, CV_8UC1, cv::Scalar(90)));
  expect_refused(sim("seq_sizes_run", "--sequence " + q(seq)), {"left1.png", "64x48 does not match", "right1.png"});
}

TEST_CASE("calibration files: unknown keys and a rig wider than the IP's RECT_RADIUS", "[calib]") {
  fs::create_directories(kTmp);
  sm::CalibFile c;
  c.width = 64;
  c.height = 48;
  c.left = sm::RectGrid::identity(64, 48);
  c.right = c.left;
  c.rect_radius_needed = 2;
  const fs::path good = kTmp / "calib_good.json";
  sm::save_calib(good.string(), c);
  const auto ok = sim("calib_good_run", "--frames 1 --calib " + q(good));
  INFO(ok.err);
  REQUIRE(ok.rc == 0);        // the file itself is fine: the refusals below are for their one change
  c.rect_radius_needed = 50;  // the small IP is built with RECT_RADIUS 4
  const fs::path wide = kTmp / "calib_wide.json";
  sm::save_calib(wide.string(), c);
  expect_refused(sim("calib_wide_run", "--frames 1 --calib " + q(wide)), {wide.string(), "rect_radius_needed", "4"});
  nlohmann::json j = nlohmann::json::parse(sm::test::slurp(good));
  j["colour"] = "blue";
  const fs::path extra = kTmp / "calib_unknown_key.json";
  std::ofstream(extra) << j.dump() << "\n";
  expect_refused(sim("calib_unknown_run", "--frames 1 --calib " + q(extra)), {extra.string(), "colour"});
}

TEST_CASE("--video: a truncated video and a file that is no video are errors", "[video]") {
  fs::create_directories(kTmp);
  const fs::path vid = kTmp / "four.avi";
  {
    cv::VideoWriter w(vid.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0, cv::Size(128, 48), true);
    REQUIRE(w.isOpened());
    const sm::tools::SyntheticScene s = sm::tools::render_scene(sm::test::scene_params(64, 48, 16, 3, 2));
    cv::Mat sbs, bgr;
    cv::hconcat(s.left, s.right, sbs);
    cv::cvtColor(sbs, bgr, cv::COLOR_GRAY2BGR);
    for (int i = 0; i < 4; ++i) w.write(bgr);
  }
  const auto whole = sim("video_whole", "--frames 4 --video " + q(vid));
  INFO(whole.err);
  REQUIRE(whole.rc == 0);  // the untruncated video runs
  // Cut after the first frame's data (the header still declares 4 frames).
  const std::string bytes = sm::test::slurp(vid);
  const fs::path cut = kTmp / "cut.avi";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 3 / 5);
  expect_refused(sim("video_cut", "--frames 4 --video " + q(cut)), {cut.string(), "of the 4 frames", "truncated"});
  // A file that is nothing: one line.
  const fs::path text = kTmp / "text.avi";
  std::ofstream(text) << "not a video\n";
  expect_refused(sim("video_text", "--video " + q(text)), {text.string(), "not a video"});
  // A PNG is no video: one clean line, no FFmpeg chatter.
  const fs::path png = kTmp / "picture.png";
  cv::imwrite(png.string(), cv::Mat(48, 128, CV_8UC1, cv::Scalar(7)));
  const auto r = sim("video_png", "--video " + q(png));
  CHECK(r.err.find("@ 0x") == std::string::npos);
  expect_refused(r, {png.string(), "not a video"});
}

TEST_CASE("-q keeps the 'input resized' note: it is a warning, not progress", "[resized_note]") {
  const fs::path sc = make_scene("note_scene", false, false);
  // --width 48: the 64-wide scene is resized
  const auto r = sim("note_run", "--frames 1 --width 48 --scene " + q(sc));
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("note: input resized to the active size 48x48") != std::string::npos);
}

TEST_CASE("steady-state frame period: measured on frames followed by another, never below the camera's frame",
          "[frame_period]") {
  // With 2 lines of vertical blanking the last frame, which no input follows, drains
  // faster than the camera's frame (5776 cycles here against 7200): the period left it
  // in (it measured the last two frames' ends).
  for (int frames : {3, 4, 6}) {
    const auto r = sim("period_" + std::to_string(frames), "--vblank 2 --frames " + std::to_string(frames));
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const double camera = (64.0 + 80) * (48 + 2) * r.report.at("clocks_per_pixel").get<int>();
    const auto period = r.report.at("steady_state_frame_period_cycles").get<double>();
    CHECK(period >= camera);
    CHECK(period <= camera + 1);
    // and it is what the frames' own cycles say, frame 0 to the last frame with a successor
    const auto& fr = r.report.at("frame_results");
    const double span = fr.at(frames - 2).at("cycles").at("last_out").get<double>() -
                        fr.at(0).at("cycles").at("last_out").get<double>();
    CHECK(period == Approx(span / (frames - 2)).margin(0.5));
  }
  const auto two = sim("period_2", "--frames 2");
  REQUIRE(two.rc == 0);
  CHECK(two.report.at("steady_state_frame_period_cycles") == 0);  // not measured
}

TEST_CASE("--core-mhz asks for the 30 frames/s check: a NO is exit code 3", "[budget]") {
  // Camera pixel clock 0.3024 MHz; the folded IP needs 4 aclk per pixel.
  const auto no = sim("budget_no", "--frames 2 --core-mhz 0.5", SM_STEREO_SIM_SMALL_FOLD);
  INFO(no.err << no.out);
  CHECK(no.rc == 3);
  CHECK(no.report.at("meets_30fps_with_camera_at_core_clock") == false);
  CHECK(no.report.at("bit_exact") == true);
  const auto yes = sim("budget_yes", "--frames 2 --core-mhz 2", SM_STEREO_SIM_SMALL_FOLD);
  CHECK(yes.rc == 0);
  CHECK(yes.report.at("meets_30fps_with_camera_at_core_clock") == true);
}

TEST_CASE("Ctrl-C during a wave dump removes the partial wave file and ends the progress line", "[sigint]") {
  const fs::path dir = sm::test::fresh_dir(kTmp / "sigint");
  const fs::path wave = dir / "top.vcd", part = dir / "top.part.vcd", err = dir / "stderr.txt";
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    // A long window: every cycle of 4000 frames (minutes), so that the signal lands mid-dump.
    const std::string cmd = std::string("exec \"") + SM_STEREO_SIM_SMALL + "\" --frames 4000 --vcd \"" + wave.string() +
                            "\" --vcd-cycles 100000000 --out \"" + (dir / "out").string() + "\" 2> \"" + err.string() +
                            "\" > /dev/null";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  bool seen = false;
  for (int i = 0; i < 600 && !seen; ++i) {
    std::error_code ec;
    // the first progress line (after 3 s: "stereo_sim: frame F/N row ...") is out
    seen = fs::file_size(part, ec) > 0 && !ec && sm::test::slurp(err).find("frame ") != std::string::npos;
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  CHECK(seen);
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  CHECK(WIFSIGNALED(st));
  CHECK(WTERMSIG(st) == SIGINT);
  CHECK_FALSE(fs::exists(part));
  CHECK_FALSE(fs::exists(wave));
  CHECK_FALSE(fs::exists(dir / "out" / "report.json"));
  const std::string e = sm::test::slurp(err);
  REQUIRE(!e.empty());
  CHECK(e.back() == '\n');
}
