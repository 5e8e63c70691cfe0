// Command-line tools end to end: bad inputs give a non-zero exit, exactly one error line
// naming the problem and no output file; good inputs give the documented outputs.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/sm_io.hpp"
#include "common/sm_scenegen.hpp"
#include "pipeline.hpp"
#include "sm_cmd.hpp"

namespace fs = std::filesystem;

namespace {

using Run = sm::test::CmdResult;
using sm::test::slurp;

fs::path tmp_root() { return fs::path(SM_TEST_TMP) / "cli"; }

Run run(const std::string& exe, const std::string& args) { return sm::test::run_cmd(exe, args, tmp_root()); }

// Non-zero exit, exactly one line on stderr mentioning `what`.
void expect_error(const Run& r, const std::string& what) {
  INFO("stderr: " << r.err);
  CHECK(r.rc != 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(what) != std::string::npos);
}

// The scratch folder holds no file other than `keep` (no partial or temporary outputs).
void expect_only(const fs::path& dir, std::vector<std::string> keep) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    INFO("unexpected file " << e.path());
    CHECK(std::find(keep.begin(), keep.end(), n) != keep.end());
  }
}

struct Fixture {
  fs::path dir, scene, in;
  sm::tools::SceneParams p;
  Fixture() {
    fs::create_directories(tmp_root());
    p.width = 64;
    p.height = 48;
    p.levels = 16;
    p.seed = 2;
    p.objects = 3;
    dir = tmp_root() / "fx";
    fs::remove_all(dir);
    scene = dir / "dataset" / "small";
    in = dir / "in";
    fs::create_directories(in);
    sm::tools::write_scene(sm::tools::render_scene(p), p, scene.string());
    // Broken inputs.
    std::ofstream((in / "text.png").string()) << "definitely not a PNG\n";
    const std::string png = slurp(scene / "left.png");
    std::ofstream((in / "trunc.png").string(), std::ios::binary) << png.substr(0, png.size() / 2);
    cv::Mat narrow = cv::imread((scene / "right.png").string(), cv::IMREAD_GRAYSCALE)(cv::Rect(0, 0, 60, 48)).clone();
    cv::imwrite((in / "narrow.png").string(), narrow);
    std::ofstream((in / "bad.json").string()) << "{ \"occ\": ";
    std::ofstream((in / "unknown.json").string()) << "{ \"occc\": 3 }";
  }
  std::string L() const { return (scene / "left.png").string(); }
  std::string R() const { return (scene / "right.png").string(); }
  std::string I(const char* f) const { return (in / f).string(); }
};

}  // namespace

TEST_CASE("stereo_model rejects bad inputs cleanly", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = fx.dir / "out";
  fs::create_directories(out);
  const std::string o = " -o " + (out / "d.png").string();
  SECTION("missing file") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.I("nope.png") + " " + fx.R() + o), "nope.png: no such file");
  }
  SECTION("not a PNG") { expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.I("text.png") + o), "text.png"); }
  SECTION("truncated PNG") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.I("trunc.png") + " " + fx.R() + o), "truncated");
  }
  SECTION("size mismatch") { expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.I("narrow.png") + o), "differs"); }
  SECTION("size above MAX_WIDTH") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + o + " --disp 16 --max-width 32"), "above MAX_WIDTH");
  }
  SECTION("malformed --regs") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + o + " --regs " + fx.I("bad.json")), "malformed JSON");
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + o + " --regs " + fx.I("unknown.json")), "occc");
  }
  SECTION("illegal parameter") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + o + " --disp 15"), "disp 15");
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + o + " --disp 16 --occ 300"), "occ");
  }
  SECTION("missing calibration") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + o + " --disp 16 --calib " + fx.I("none.json")),
                 "none.json");
  }
  SECTION("unwritable output") {
    expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --disp 16 -o " + (out / "no" / "d.png").string()),
                 "cannot write");
  }
  expect_only(out, {});
}

TEST_CASE("stereo_model writes the model's disparity", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = fx.dir / "out_ok";
  fs::remove_all(out);
  fs::create_directories(out);
  const Run r = run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --disp 16 --census 7 --sw 3 --occ 20 -v -o " +
                                             (out / "d.png").string() + " --objects-json " + (out / "o.json").string());
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("census") != std::string::npos);  // -v: per-stage timing
  expect_only(out, {"d.png", "d_colour.png", "o.json"});
  const cv::Mat d = cv::imread((out / "d.png").string(), cv::IMREAD_UNCHANGED);
  REQUIRE(d.type() == CV_8UC1);
  REQUIRE(d.size() == cv::Size(64, 48));
  CHECK(cv::imread((out / "d_colour.png").string(), cv::IMREAD_UNCHANGED).type() == CV_8UC3);
  // Same image as the model run directly with the same parameters.
  sm::HwConfig hw;
  hw.max_width = 64;
  hw.max_height = 48;
  hw.disp = 16;
  hw.census = 7;
  hw.sw = 3;
  sm::Regs regs = sm::Regs::defaults(hw);
  regs.occ = 20;
  const auto res = sm::run_pipeline(sm::tools::load_grey(fx.L()), sm::tools::load_grey(fx.R()), hw, regs, false);
  const cv::Mat ref = sm::tools::disp_to_grey(sm::tools::disp_to_float(res.post), 16);
  CHECK(cv::norm(d, ref, cv::NORM_INF) == 0);
  const auto j = nlohmann::json::parse(slurp(out / "o.json"));
  CHECK(j["objects"].size() == res.objects.objects.size());
  // --regs file gives the same result as the options.
  std::ofstream((out / "r.json").string()) << R"({"disp": 16, "census": 7, "sw": 3, "occ": 20})";
  const Run r2 = run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --regs " + (out / "r.json").string() + " -o " +
                                              (out / "d2.png").string());
  REQUIRE(r2.rc == 0);
  CHECK(cv::norm(cv::imread((out / "d2.png").string(), cv::IMREAD_UNCHANGED), ref, cv::NORM_INF) == 0);
}

TEST_CASE("sm_evaluate rejects bad datasets cleanly", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = fx.dir / "eval_bad";
  fs::create_directories(out);
  const std::string j = " --json " + (out / "r.json").string();
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "nowhere").string() + j), "nowhere: not a directory");
  expect_error(run(SM_EVALUATE_EXE, fx.in.string() + j), "no scenes");
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --scenes tsukuba" + j), "no scene 'tsukuba'");
  // A scene with a truncated ground truth / mismatched right image.
  const fs::path broken = fx.dir / "broken" / "s";
  fs::create_directories(broken);
  for (const char* f : {"left.png", "right.png", "nonocc.png", "scale.txt"}) fs::copy_file(fx.scene / f, broken / f);
  fs::copy_file(fx.in / "trunc.png", broken / "gt.png");
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "broken").string() + " -q" + j), "gt.png");
  fs::copy_file(fx.scene / "gt.png", broken / "gt.png", fs::copy_options::overwrite_existing);
  fs::copy_file(fx.in / "narrow.png", broken / "right.png", fs::copy_options::overwrite_existing);
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "broken").string() + " -q" + j), "differ in size");
  expect_only(out, {});
}

TEST_CASE("sm_evaluate reports every method on a synthetic scene", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = fx.dir / "eval_ok";
  fs::remove_all(out);
  fs::create_directories(out);
  const Run r = run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --levels 16 -q --json " +
                                         (out / "r.json").string() + " --disp-images " + (out / "img").string());
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("mean") != std::string::npos);
  const auto j = nlohmann::json::parse(slurp(out / "r.json"));
  REQUIRE(j["scenes"].size() == 1);
  const auto& s = j["scenes"][0];
  CHECK(s["name"] == "small");
  const cv::Mat nonocc = cv::imread((fx.scene / "nonocc.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat gt = cv::imread((fx.scene / "gt.png").string(), cv::IMREAD_ANYDEPTH);
  const long expect = cv::countNonZero(nonocc & (gt > 0));
  for (const char* m : {"model", "bm", "sgbm", "binsgbm"}) {
    INFO(m);
    REQUIRE(s["methods"].contains(m));
    CHECK(s["methods"][m]["evaluated"] == expect);
    CHECK(s["methods"][m]["bad1_pct"].get<double>() >= 0.0);
    CHECK(s["methods"][m]["bad1_pct"].get<double>() <= 100.0);
    CHECK(fs::exists(out / "img" / ("small_" + std::string(m) + ".png")));
  }
  // StereoBM leaves the leftmost numDisparities columns invalid: they show up as invalid.
  CHECK(s["methods"]["bm"]["invalid"].get<long>() > 0);
}

TEST_CASE("sm_evaluate on in-memory synthetic scenes", "[unit][tools][cli]") {
  fs::create_directories(tmp_root());
  const fs::path j = tmp_root() / "synth.json";
  fs::remove(j);
  const Run r = run(SM_EVALUATE_EXE,
                    "--synthetic 2 --synthetic-size 48x32 --levels 16 -q --methods "
                    "model,sgbm --occ 10 --json " +
                        j.string());
  INFO(r.err);
  REQUIRE(r.rc == 0);
  const auto js = nlohmann::json::parse(slurp(j));
  REQUIRE(js["scenes"].size() == 2);
  CHECK(js["scenes"][1]["name"] == "synthetic2");
  CHECK(js["scenes"][0]["width"] == 48);
  CHECK(js["scenes"][0]["methods"].size() == 2);
  expect_error(run(SM_EVALUATE_EXE, "--synthetic 1 --synthetic-size 48by32"), "48by32");
  expect_error(run(SM_EVALUATE_EXE, "--levels 15 --synthetic 1"), "--levels 15");
}

TEST_CASE("sm_scene rejects bad parameters cleanly", "[unit][tools][cli]") {
  fs::create_directories(tmp_root());
  const fs::path out = tmp_root() / "scene_bad";
  fs::remove_all(out);
  fs::create_directories(out);
  expect_error(run(SM_SCENE_EXE, "--out " + out.string() + " --width 8"), "image size");
  expect_error(run(SM_SCENE_EXE, "--out " + out.string() + " --levels 16 --bg-disp 30"), "exceeds levels");
  std::ofstream((out / "file").string()) << "x";
  expect_error(run(SM_SCENE_EXE, "--out " + (out / "file").string()), "cannot create directory");
  expect_only(out, {"file"});
}
