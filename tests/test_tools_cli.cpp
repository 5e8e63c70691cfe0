// Command-line tools end to end: bad inputs give a non-zero exit, exactly one error line
// naming the problem and no output file; good inputs give the documented outputs.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <sstream>

#include "calib_file.hpp"
#include "toolio/sm_host_speckle.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_scenegen.hpp"
#include "outword.hpp"
#include "smooth.hpp"
#include "configs.hpp"
#include "speckle.hpp"
#include "pipeline.hpp"
#include "sm_chessboard_rig.hpp"
#include "sm_cmd.hpp"
#include "sm_test_util.hpp"

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
    p = sm::test::scene_params(64, 48, 16, 2, 3);
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
    std::ofstream((in / "range.json").string()) << "{ \"occ\": 300 }";
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
  // stereo_model on the fixture's pair (L R) with `args`, or on `pair` instead
  auto model = [&](const std::string& args, const std::string& pair = "") {
    return run(SM_STEREO_MODEL_EXE, (pair.empty() ? fx.L() + " " + fx.R() : pair) + args);
  };
  SECTION("missing file") { expect_error(model(o, fx.I("nope.png") + " " + fx.R()), "nope.png: no such file"); }
  SECTION("not a PNG") { expect_error(model(o, fx.L() + " " + fx.I("text.png")), "text.png"); }
  SECTION("truncated PNG") { expect_error(model(o, fx.I("trunc.png") + " " + fx.R()), "truncated"); }
  SECTION("size mismatch") { expect_error(model(o, fx.L() + " " + fx.I("narrow.png")), "differs"); }
  SECTION("size above MAX_WIDTH") { expect_error(model(o + " --disp 16 --max-width 32"), "above MAX_WIDTH"); }
  SECTION("malformed --regs") {
    expect_error(model(o + " --regs " + fx.I("bad.json")), "malformed JSON");
    expect_error(model(o + " --regs " + fx.I("unknown.json")), "occc");
    // a register out of range: the file, the key, the value and the range (set_register's wording)
    expect_error(model(o + " --regs " + fx.I("range.json")), "range.json: 'occ' = 300 is outside 0..255");
  }
  SECTION("illegal parameter") {
    expect_error(model(o + " --disp 15"), "--disp: 15: must be even, 4..254");
    // the option, the value and the range: the same wording as a register file's key
    expect_error(model(o + " --disp 16 --occ 300"), "--occ = 300 is outside 0..255");
  }
  SECTION("missing calibration") { expect_error(model(o + " --disp 16 --calib " + fx.I("none.json")), "none.json"); }
  SECTION("bad thread count") { expect_error(model(o + " --disp 16 --threads 0"), "--threads"); }
  SECTION("bad speckle check") {
    expect_error(model(o + " --disp 16 --speckle 10,300"), "--speckle: 300: outside 0..255");
    expect_error(model(o + " --disp 16 --speckle many"), "--speckle: 'many': not an integer");
    expect_error(model(o + " --disp 16 --speckle ,8"), "--speckle: '': not an integer");
    expect_error(model(o + " --disp 16 --speckle 10,8,2"), "--speckle: '10,8,2': expected SIZE or SIZE,DIFF");
    expect_error(model(o + " --disp 16 --speckle 10,"), "expected SIZE or SIZE,DIFF");
    expect_error(model(o + " --disp 16 --speckle 10 --speckle 20"), "--speckle");
  }
  SECTION("empty item in a list") {  // CLI11 alone would drop it and run on a shorter list
    expect_error(model(o + " --disp 16 --sw-table 1,,2"), "--sw-table: '1,,2': an empty item in a ','-separated list");
    expect_error(model(o + " --disp 16 --sw-table=1,2,"), "--sw-table: '1,2,': an empty item");
  }
  SECTION("unwritable output") {
    expect_error(model(" --disp 16 -o " + (out / "no" / "d.png").string()), "cannot write");
  }
  expect_only(out, {});
}

TEST_CASE("stereo_model writes the model's disparity", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = sm::test::fresh_dir(fx.dir / "out_ok");
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
  // --threads: the same image.
  const Run r3 =
      run(SM_STEREO_MODEL_EXE,
          fx.L() + " " + fx.R() + " --disp 16 --census 7 --sw 3 --occ 20 --threads 3 -o " + (out / "d3.png").string());
  REQUIRE(r3.rc == 0);
  CHECK(cv::norm(cv::imread((out / "d3.png").string(), cv::IMREAD_UNCHANGED), ref, cv::NORM_INF) == 0);
  // --config: a named configuration's parameters (small: DISP 16, CENSUS 7, SW 3, RECT_RADIUS 4),
  // the sizes the image's; zynq's 128 levels do not fit a 64-pixel line
  sm::HwConfig small = sm::named_config("small");
  const sm::PipelineResult res4 =
      sm::run_pipeline(sm::tools::load_grey(fx.L()), sm::tools::load_grey(fx.R()), small, regs, false);
  const Run r4 =
      run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --config small --occ 20 -o " + (out / "d4.png").string());
  REQUIRE(r4.rc == 0);
  CHECK(cv::norm(cv::imread((out / "d4.png").string(), cv::IMREAD_UNCHANGED),
                 sm::tools::disp_to_grey(sm::tools::disp_to_float(res4.post), 16), cv::NORM_INF) == 0);
  expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --config zynq -o " + (out / "d5.png").string()),
               "bad hardware configuration");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --config zynq7020 -o " + (out / "d5.png").string()),
               "--config");
  CHECK_FALSE(fs::exists(out / "d5.png"));
}

TEST_CASE("sm_evaluate rejects bad datasets cleanly", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = fx.dir / "eval_bad";
  fs::create_directories(out);
  const std::string j = " --json " + (out / "r.json").string();
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "nowhere").string() + j), "nowhere: not a directory");
  expect_error(run(SM_EVALUATE_EXE, fx.in.string() + j), "no scenes");
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --scenes tsukuba" + j), "no scene 'tsukuba'");
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --speckle-rows 63" + j),
               "--speckle-rows: 63: outside 0..62");
  expect_error(run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --scenes small,,small" + j),
               "--scenes: 'small,,small': an empty item");
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
  const fs::path out = sm::test::fresh_dir(fx.dir / "eval_ok");
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
  // Every method, the model after each post-processing step, the dense peer variants.
  const cv::Mat gtf = [&] {
    cv::Mat f;
    gt.convertTo(f, CV_32F, 1.0 / sm::tools::kGtScale);
    return f;
  }();
  const long smooth = sm::tools::streaks(gtf, gtf, nonocc).smooth;
  REQUIRE(smooth > 0);
  for (const char* m : {"model_dp", "model_f0", "model_f1", "model_f1f2", "model", "bm", "bm-dense", "sgbm",
                        "sgbm-dense", "sgbm-hh", "sgbm-hh-dense", "binsgbm", "binsgbm-dense"}) {
    INFO(m);
    REQUIRE(s["methods"].contains(m));
    const auto& e = s["methods"][m];
    CHECK(e["evaluated"] == expect);
    CHECK(e["bad1_pct"].get<double>() >= 0.0);
    CHECK(e["bad1_pct"].get<double>() <= 100.0);
    CHECK(e["smooth"] == smooth);
    REQUIRE(e["streak"].size() == 2);  // default --streak-rows 1,5
    CHECK(e["streak"][0]["max_rows"] == 1);
    CHECK(e["streak"][1]["max_rows"] == 5);
    CHECK(e["streak"][0]["pixels"].get<long>() <= e["streak"][1]["pixels"].get<long>());
    CHECK(e["streak"][1]["pixels"].get<long>() <= e["bad"].get<long>());
    CHECK(fs::exists(out / "img" / ("small_" + std::string(m) + ".png")));
    // The peers run at the scene's own range (16 levels), the model at --levels.
    CHECK(e["levels"] == 16);
    REQUIRE(j["mean"].contains(m));
  }
  CHECK(s["peer_levels"] == 16);
  CHECK(s["methods"]["model"]["ms"].is_number());
  CHECK(s["methods"]["model_dp"]["ms"].is_null());  // the steps come from the model's one run
  // StereoBM leaves the leftmost numDisparities columns invalid: they show up as invalid;
  // the dense variants never have more invalid pixels than the filtered ones.
  CHECK(s["methods"]["bm"]["invalid"].get<long>() > 0);
  for (const char* m : {"bm", "sgbm", "sgbm-hh", "binsgbm"})
    CHECK(s["methods"][std::string(m) + "-dense"]["invalid"].get<long>() <= s["methods"][m]["invalid"].get<long>());
  // The output stage (issue 39): the dense sub-pixel output has every pixel valid and a
  // confidence; the checked one leaves pixels invalid; the accuracy block agrees with bad1.
  for (const char* m : {"model", "model_subpix", "model_checked", "model_host", "sgbm"}) {
    INFO(m);
    const auto& a = s["methods"][m]["accuracy"];
    CHECK(a["bad1_pct"].get<double>() == Approx(s["methods"][m]["bad1_pct"].get<double>()));
    CHECK(a["bad05_pct"].get<double>() >= a["bad1_pct"].get<double>());
    CHECK(a["bad1_pct"].get<double>() >= a["bad2_pct"].get<double>());
    CHECK(a["density_pct"].get<double>() <= 100.0);
  }
  CHECK(s["methods"]["model_subpix"]["accuracy"]["density_pct"] == 100.0);
  CHECK(s["methods"]["model_checked"]["accuracy"]["density_pct"].get<double>() < 100.0);
  CHECK(s["methods"]["model_host"]["accuracy"]["density_pct"].get<double>() < 100.0);
  const auto& sp = s["methods"]["model_subpix"]["accuracy"]["sparsification"];
  REQUIRE(sp["curve"].size() == 100);
  CHECK(sp["auc"].get<double>() >= sp["oracle_auc"].get<double>());
  CHECK_FALSE(s["methods"]["model"]["accuracy"].contains("sparsification"));
  // Console: the tables with their mean rows.
  for (const char* t :
       {"bad-1.0 %", "streak % (streaks up to 1 row thick", "up to 5 rows thick", "ms per frame", "bad-0.5 %",
        "bad-2.0 %", "mean absolute error", "density %", "bad-1.0 % over the valid", "sparsification"})
    CHECK(r.out.find(t) != std::string::npos);
  // --peer-levels: the peers at the given numDisparities, the model unchanged.
  const Run r2 = run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --levels 16 --peer-levels 32 -q " +
                                          "--methods model,bm --streak-rows 2 --json " + (out / "r2.json").string());
  INFO(r2.err);
  REQUIRE(r2.rc == 0);
  const auto j2 = nlohmann::json::parse(slurp(out / "r2.json"));
  CHECK(j2["scenes"][0]["peer_levels"] == 32);
  CHECK(j2["scenes"][0]["methods"]["bm"]["levels"] == 32);
  CHECK(j2["scenes"][0]["methods"]["model"]["levels"] == 16);
  CHECK(j2["scenes"][0]["methods"]["model"]["bad1_pct"] == s["methods"]["model"]["bad1_pct"]);
  CHECK(j2["scenes"][0]["methods"]["model"]["streak"][0]["max_rows"] == 2);
  CHECK(j2["scenes"][0]["methods"].size() == 9);  // the model's eight outputs and bm
  // --config: the model at a named configuration's parameters (small: census 7, SW 3), the
  // same as those parameters from a register file, and recorded in the JSON
  const fs::path small_regs = out / "small.json";
  std::ofstream(small_regs) << R"({"census": 7, "sw": 3, "rect_radius": 4})";
  const std::string model16 = (fx.dir / "dataset").string() + " --levels 16 -q --methods model --json ";
  const Run r3 = run(SM_EVALUATE_EXE, model16 + (out / "r3.json").string() + " --config small");
  const Run r4 = run(SM_EVALUATE_EXE, model16 + (out / "r4.json").string() + " --regs " + small_regs.string());
  REQUIRE(r3.rc == 0);
  REQUIRE(r4.rc == 0);
  const auto j3 = nlohmann::json::parse(slurp(out / "r3.json")), j4 = nlohmann::json::parse(slurp(out / "r4.json"));
  CHECK(j3["model_config"] == "small");
  CHECK(j["model_config"] == "paper");
  // --speckle-rows is recorded when given, 0 included, and only then
  const Run r5 = run(SM_EVALUATE_EXE, model16 + (out / "r5.json").string() + " --speckle-rows 0");
  REQUIRE(r5.rc == 0);
  CHECK(nlohmann::json::parse(slurp(out / "r5.json"))["model_speckle_rows"] == 0);
  CHECK(!j.contains("model_speckle_rows"));
  const auto& m3 = j3["scenes"][0]["methods"]["model"];
  CHECK(m3["bad1_pct"] == j4["scenes"][0]["methods"]["model"]["bad1_pct"]);
  CHECK(m3["bad1_pct"] != s["methods"]["model"]["bad1_pct"]);
  const std::string ds = (fx.dir / "dataset").string() + " -q";
  expect_error(run(SM_EVALUATE_EXE, ds + " --config zynq7020"), "--config");
  expect_error(run(SM_EVALUATE_EXE, ds + " --peer-levels 40"), "--peer-levels 40");
  expect_error(run(SM_EVALUATE_EXE, ds + " --methods model,bm,model"), "twice");
  expect_only(out, {"r.json", "r2.json", "r3.json", "r4.json", "r5.json", "small.json", "img"});
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
  // model_dp, model_f0, model_f1, model_f1f2, model, model_subpix, model_checked, model_host, sgbm
  CHECK(js["scenes"][0]["methods"].size() == 9);
  expect_error(run(SM_EVALUATE_EXE, "--synthetic 1 --synthetic-size 48by32"), "48by32");
  expect_error(run(SM_EVALUATE_EXE, "--levels 15 --synthetic 1"), "--levels 15: must be 0 (per scene) or even, 4..254");
}

TEST_CASE("sm_scene rejects bad parameters cleanly", "[unit][tools][cli]") {
  fs::create_directories(tmp_root());
  const fs::path out = tmp_root() / "scene_bad";
  fs::remove_all(out);
  fs::create_directories(out);
  expect_error(run(SM_SCENE_EXE, "--out " + out.string() + " --width 8"), "--width: 8: outside 16..4095");
  expect_error(run(SM_SCENE_EXE, "--out " + out.string() + " --levels 16 --bg-disp 30"), "exceeds levels");
  std::ofstream((out / "file").string()) << "x";
  expect_error(run(SM_SCENE_EXE, "--out " + (out / "file").string()), "file: cannot write: not a folder");
  expect_only(out, {"file"});
}

namespace {

// "--name TYPE=value" defaults from a CLI11 --help text (option name -> value).
std::map<std::string, std::string> help_defaults(const std::string& help) {
  std::map<std::string, std::string> d;
  const std::regex re(R"((--[a-z][a-z-]*)[^\n]*?\S=(\S+))");
  std::stringstream ss(help);
  std::string line;
  while (std::getline(ss, line)) {
    std::smatch m;
    if (std::regex_search(line, m, re)) d[m[1]] = m[2];
  }
  return d;
}

}  // namespace

TEST_CASE("--help shows the model's own defaults", "[unit][tools][cli]") {
  fs::create_directories(tmp_root());
  const sm::HwConfig hw;
  const sm::Regs r = sm::Regs::defaults(hw);
  std::string sw_table;
  for (int i = 0; i < 8; ++i) sw_table += (i ? "," : "") + std::to_string(r.sw_table[i]);
  for (int i = 8; i < 32; ++i) REQUIRE(r.sw_table[i] == 0);  // the help shows the non-zero head
  {
    const Run h = run(SM_STEREO_MODEL_EXE, "--help");
    REQUIRE(h.rc == 0);
    const auto d = help_defaults(h.out);
    const std::map<std::string, long> want = {{"--disp", hw.disp},
                                              {"--census", hw.census},
                                              {"--sw", hw.sw},
                                              {"--rect-radius", hw.rect_radius},
                                              {"--cost-shift", hw.cost_shift},
                                              {"--max-objects", hw.max_objects},
                                              {"--label-slots", hw.label_slots},
                                              {"--band-k", hw.band_k},
                                              {"--gain-l", r.gain_l},
                                              {"--gain-r", r.gain_r},
                                              {"--offset-l", r.offset_l},
                                              {"--offset-r", r.offset_r},
                                              {"--occ", r.occ},
                                              {"--occ-edge", r.occ_edge},
                                              {"--edge-t", r.edge_t},
                                              {"--filter-enable", r.filter_enable},
                                              {"--obj-near", r.obj_near},
                                              {"--obj-tol", r.obj_tol},
                                              {"--obj-min-pixels", r.obj_min_pixels}};
    for (const auto& [name, v] : want) {
      INFO(name << "\n" << h.out);
      REQUIRE(d.count(name));
      CHECK(d.at(name) == std::to_string(v));
    }
    INFO(h.out);
    REQUIRE(d.count("--sw-table"));
    CHECK(d.at("--sw-table") == sw_table);
    CHECK(r.rect_enable);  // --no-rect is a flag: off by default, as rect_enable = 1
  }
  // sm_evaluate and sm_calibrate: each option's default as the help shows it
  const std::vector<std::pair<std::string, std::map<std::string, std::string>>> tools = {
      {SM_EVALUATE_EXE,
       {{"--levels", std::to_string(hw.disp)},
        {"--occ", std::to_string(r.occ)},
        {"--synthetic-size", std::to_string(hw.max_width) + "x" + std::to_string(hw.max_height)}}},
      {SM_CALIBRATE_EXE,
       {{"--rect-radius", std::to_string(hw.rect_radius)},
        {"--width", std::to_string(hw.max_width)},
        {"--height", std::to_string(hw.max_height)}}}};
  for (const auto& [exe, want] : tools) {
    const Run h = run(exe, "--help");
    REQUIRE(h.rc == 0);
    const auto d = help_defaults(h.out);
    INFO(h.out);
    for (const auto& [name, v] : want) {
      REQUIRE(d.count(name));
      CHECK(d.at(name) == v);
    }
  }
}

namespace {

// A PFM that stereo_model wrote holds `want` (CV_32F): its valid values exactly, +infinity
// where `want` is invalid (negative).
void check_pfm(const fs::path& pfm, const cv::Mat& want) {
  const cv::Mat raw = cv::imread(pfm.string(), cv::IMREAD_UNCHANGED);
  REQUIRE(raw.type() == CV_32FC1);
  REQUIRE(raw.size() == want.size());
  for (int y = 0; y < want.rows; ++y)
    for (int x = 0; x < want.cols; ++x) {
      const float e = want.at<float>(y, x), g = raw.at<float>(y, x);
      if (e < 0)
        CHECK(std::isinf(g));
      else
        CHECK(g == e);
    }
}

}  // namespace

TEST_CASE("stereo_model --disp-file writes the disparity losslessly", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = sm::test::fresh_dir(fx.dir / "out_lossless");
  sm::HwConfig hw;
  hw.max_width = 64;
  hw.max_height = 48;
  hw.disp = 16;
  const auto res =
      sm::run_pipeline(sm::tools::load_grey(fx.L()), sm::tools::load_grey(fx.R()), hw, sm::Regs::defaults(hw), false);
  const cv::Mat ref = sm::tools::disp_to_float(res.post);
  REQUIRE(cv::countNonZero(ref >= 0) > 0);
  const std::string lr = fx.L() + " " + fx.R() + " --disp 16";
  SECTION("PFM: float disparity, +inf = invalid") {
    const Run r = run(SM_STEREO_MODEL_EXE, lr + " --disp-file " + (out / "d.pfm").string());
    INFO(r.err);
    REQUIRE(r.rc == 0);
    expect_only(out, {"d.pfm"});  // no viewing PNGs unless asked for
    check_pfm(out / "d.pfm", ref);
  }
  SECTION("16-bit PNG: disparity x 16, 0 = invalid; viewing PNGs alongside") {
    const Run r =
        run(SM_STEREO_MODEL_EXE, lr + " --disp-file " + (out / "d16.png").string() + " -o " + (out / "g.png").string());
    INFO(r.err);
    REQUIRE(r.rc == 0);
    expect_only(out, {"d16.png", "g.png", "g_colour.png"});
    const cv::Mat raw = cv::imread((out / "d16.png").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(raw.type() == CV_16UC1);
    cv::Mat want(ref.size(), CV_16UC1);
    for (int y = 0; y < ref.rows; ++y)
      for (int x = 0; x < ref.cols; ++x) {
        const float e = ref.at<float>(y, x);
        want.at<uint16_t>(y, x) = e < 0 ? 0 : static_cast<uint16_t>(e * 16);
      }
    CHECK(cv::norm(raw, want, cv::NORM_INF) == 0);
    CHECK(cv::norm(cv::imread((out / "g.png").string(), cv::IMREAD_UNCHANGED), sm::tools::disp_to_grey(ref, 16),
                   cv::NORM_INF) == 0);
  }
  SECTION("--mode dense / checked: the planned output word's Q.4 disparity and its confidence") {
    for (const char* mode : {"dense", "checked"}) {
      INFO(mode);
      const fs::path f = out / (std::string(mode) + ".png"), c = out / (std::string(mode) + "_conf.png");
      const Run r = run(SM_STEREO_MODEL_EXE,
                        lr + " --mode " + mode + " --disp-file " + f.string() + " --confidence " + c.string());
      INFO(r.err);
      REQUIRE(r.rc == 0);
      const sm::OutImage word =
          sm::stream_words(res.evidence, res.post, 16,
                           std::string(mode) == "dense" ? sm::dense_mode(sm::OutputRegs{}) : sm::OutputRegs{});
      cv::Mat want(ref.size(), CV_16UC1), conf(ref.size(), CV_8UC1);
      for (int y = 0; y < ref.rows; ++y)
        for (int x = 0; x < ref.cols; ++x) {
          const uint32_t w = word.at(x, y);
          want.at<uint16_t>(y, x) = sm::out_valid(w) ? static_cast<uint16_t>(sm::out_q4(w)) : 0;
          conf.at<uint8_t>(y, x) = static_cast<uint8_t>(sm::out_conf(w));
        }
      CHECK(cv::norm(cv::imread(f.string(), cv::IMREAD_UNCHANGED), want, cv::NORM_INF) == 0);
      CHECK(cv::norm(cv::imread(c.string(), cv::IMREAD_UNCHANGED), conf, cv::NORM_INF) == 0);
    }
    expect_error(run(SM_STEREO_MODEL_EXE, lr + " --mode checked --stage dp --disp-file " + (out / "x.pfm").string()),
                 "--stage dp");
    expect_error(run(SM_STEREO_MODEL_EXE,
                     lr + " --disp-file " + (out / "x.pfm").string() + " --confidence " + (out / "x.png").string()),
                 "--confidence needs");
    expect_only(out, {"dense.png", "dense_conf.png", "checked.png", "checked_conf.png"});
  }
  SECTION("--speckle: the host's check on the written disparity, after the IP's rules") {
    const fs::path f = out / "host.pfm";
    const Run r = run(SM_STEREO_MODEL_EXE, lr + " --mode checked --lr-en 0 --agree-en 0 --smooth-en 0 --speckle 20 -v" +
                                               " --disp-file " + f.string());
    INFO(r.err);
    REQUIRE(r.rc == 0);
    sm::OutputRegs host;
    host.lr_en = host.agree_en = host.smooth_en = 0;
    cv::Mat want = sm::tools::out_to_float(sm::stream_words(res.evidence, res.post, 16, host));
    const long cleared = sm::tools::host_speckle(want, 20, sm::tools::kHostSpeckleDiff);
    CHECK(cleared > 0);  // the fixture's pair has speckles of at most 20 px
    CHECK(r.out.find(fmt::format("host: {} of them cleared as speckles of at most 20 px", cleared)) !=
          std::string::npos);
    check_pfm(f, want);
    CHECK(r.err.find("note:") == std::string::npos);
    // with the rules the check was not measured with: written all the same, and a note says so
    const Run on = run(SM_STEREO_MODEL_EXE, lr + " --mode checked --speckle 20 --disp-file " + f.string());
    CHECK(on.rc == 0);
    CHECK(on.err.find("--speckle was measured with --lr-en 0 --agree-en 0 --smooth-en 0") != std::string::npos);
  }
  SECTION("--speckle-rows: the IP's speckle stage (9.8), which resets into its speckle mode") {
    // the words before the smoothing, the stage at 4 rows (size 20) on or off, then the smoothing
    auto stage = [&](bool rules, bool on) {
      sm::OutputRegs o;
      o.lr_en = o.agree_en = rules;
      const sm::OutImage words = sm::make_output(res.evidence, res.post, 16, o, 0);
      const sm::SpeckleRegs sr{static_cast<uint8_t>(on), 20, 8};
      return sm::smooth_output(sm::speckle_output(words, sr, 4, 1024), o.smooth_en, o.smooth_t);
    };
    const fs::path f = out / "stage.pfm";
    // the reset where the stage is built: the stage on, the left-right and agreement rules off
    const Run r =
        run(SM_STEREO_MODEL_EXE, lr + " --mode checked --speckle-rows 4 --speckle-size 20 --disp-file " + f.string());
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const sm::OutImage want = stage(false, true);
    CHECK(sm::tools::fail_counts(want).by_rule[6] > 0);  // the fixture's pair has speckles of at most 20 px
    check_pfm(f, sm::tools::out_to_float(want));
    // the stage on with the rules on
    const Run on = run(SM_STEREO_MODEL_EXE, lr +
                                                " --mode checked --speckle-rows 4 --speckle-size 20 --lr-en 1 "
                                                "--agree-en 1 --disp-file " +
                                                f.string());
    REQUIRE(on.rc == 0);
    check_pfm(f, sm::tools::out_to_float(stage(true, true)));
    // the stage off with the rules on: the words of the core without it
    const Run off = run(SM_STEREO_MODEL_EXE, lr +
                                                 " --mode checked --speckle-rows 4 --speckle-en 0 --lr-en 1 "
                                                 "--agree-en 1 --disp-file " +
                                                 f.string());
    REQUIRE(off.rc == 0);
    check_pfm(f, sm::tools::out_to_float(sm::stream_words(res.evidence, res.post, 16, sm::OutputRegs{})));
    // a register file's configuration resets the same way, and the file's own registers win,
    // also over the resets of a configuration the options change after it
    const fs::path regs = out / "regs.json";
    std::ofstream(regs) << R"({"speckle_rows": 4, "speckle_size": 20})";
    REQUIRE(
        run(SM_STEREO_MODEL_EXE, lr + " --mode checked --regs " + regs.string() + " --disp-file " + f.string()).rc ==
        0);
    check_pfm(f, sm::tools::out_to_float(stage(false, true)));
    std::ofstream(regs) << R"({"speckle_size": 20, "lr_en": 1, "agree_en": 1})";
    REQUIRE(run(SM_STEREO_MODEL_EXE,
                lr + " --mode checked --regs " + regs.string() + " --speckle-rows 4 --disp-file " + f.string())
                .rc == 0);
    check_pfm(f, sm::tools::out_to_float(stage(true, true)));
  }
  SECTION("bad requests leave no output at all") {
    expect_error(run(SM_STEREO_MODEL_EXE, lr + " --disp-file " + (out / "d.txt").string()), ".pfm or .png");
    expect_error(run(SM_STEREO_MODEL_EXE, lr), "no output");
    // the last output cannot be written: the ones before it must not stay behind either
    expect_error(
        run(SM_STEREO_MODEL_EXE, lr + " --disp-file " + (out / "d.pfm").string() + " -o " + (out / "g.png").string() +
                                     " --objects-json " + (out / "none" / "o.json").string()),
        "o.json");
    expect_only(out, {});
  }
}

TEST_CASE("sm_evaluate --results scores another program's disparity files", "[unit][tools][cli]") {
  Fixture fx;
  const fs::path out = fx.dir / "eval_results";
  fs::remove_all(out);
  const fs::path res = out / "res";
  fs::create_directories(res);
  const sm::tools::Scene sc = sm::tools::load_scene(fx.scene.string());
  const long expect = cv::countNonZero(sc.nonocc & (sc.gt > 0));
  REQUIRE(expect > 0);
  auto score = [&](const std::string& extra) {
    const fs::path j = out / "r.json";
    fs::remove(j);
    const Run r = run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --levels 16 -q --methods results --results " +
                                           res.string() + extra + " --json " + j.string());
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const auto js = nlohmann::json::parse(slurp(j));
    REQUIRE(js["scenes"].size() == 1);
    const auto& m = js["scenes"][0]["methods"]["results"];
    CHECK(m["evaluated"] == expect);
    CHECK(m["ms"].is_null());  // not run here: no time
    return m;
  };
  SECTION("PFM equal to the ground truth: 0 %, shifted by 2: 100 %") {
    sm::tools::write_disparity_file((res / "small.pfm").string(), sc.gt);
    CHECK(score("")["bad1_pct"].get<double>() == 0.0);
    sm::tools::write_disparity_file((res / "small.pfm").string(), sc.gt + 2.0);
    CHECK(score("")["bad1_pct"].get<double>() == 100.0);
    // invalid pixels (+inf) count as bad, as for the model
    cv::Mat g = sc.gt.clone();
    g.colRange(0, 8).setTo(-1.0f);
    sm::tools::write_disparity_file((res / "small.pfm").string(), g);
    const long inv = cv::countNonZero(sc.nonocc.colRange(0, 8) & (sc.gt.colRange(0, 8) > 0));
    REQUIRE(inv > 0);
    const auto m = score("");
    CHECK(m["invalid"] == inv);
    CHECK(m["bad"] == inv);
  }
  SECTION("16-bit PNG with a scale") {
    cv::Mat png;
    sc.gt.convertTo(png, CV_16U, 256.0);  // KITTI scale; gt is on a 1/256 grid
    REQUIRE(cv::imwrite((res / "small.png").string(), png));
    CHECK(score(" --results-scale 256")["bad1_pct"].get<double>() == 0.0);
    CHECK(score("")["bad1_pct"].get<double>() == 100.0);  // read at the default x16: 16 times too large
    cv::Mat shifted;
    cv::Mat(sc.gt + 2.0).convertTo(shifted, CV_16U, 16.0);
    REQUIRE(cv::imwrite((res / "small.png").string(), shifted));
    CHECK(score("")["bad1_pct"].get<double>() == 100.0);
  }
  SECTION("the same footing as the model") {
    // the model's own disparity as a result file scores exactly as the model does
    const Run m =
        run(SM_STEREO_MODEL_EXE, fx.L() + " " + fx.R() + " --disp 16 --disp-file " + (res / "small.pfm").string());
    REQUIRE(m.rc == 0);
    const Run r = run(SM_EVALUATE_EXE, (fx.dir / "dataset").string() + " --levels 16 -q --methods model --results " +
                                           res.string() + " --json " + (out / "both.json").string());
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const auto js = nlohmann::json::parse(slurp(out / "both.json"));
    const auto& ms = js["scenes"][0]["methods"];
    CHECK(ms["results"]["bad"] == ms["model"]["bad"]);
    CHECK(ms["results"]["invalid"] == ms["model"]["invalid"]);
    CHECK(ms["results"]["evaluated"] == ms["model"]["evaluated"]);
  }
  SECTION("missing, ambiguous or mis-sized result files") {
    const std::string ds = (fx.dir / "dataset").string() + " --levels 16 -q --methods results";
    expect_error(run(SM_EVALUATE_EXE, ds + " --results " + res.string()), "no small.pfm or small.png");
    expect_error(run(SM_EVALUATE_EXE, ds + " --results " + (out / "nowhere").string()), "nowhere: not a directory");
    expect_error(run(SM_EVALUATE_EXE, ds), "no --results folder");
    sm::tools::write_disparity_file((res / "small.pfm").string(), sc.gt(cv::Rect(0, 0, 60, 48)).clone());
    expect_error(run(SM_EVALUATE_EXE, ds + " --results " + res.string()), "differs");
    sm::tools::write_disparity_file((res / "small.png").string(), sc.gt);
    expect_error(run(SM_EVALUATE_EXE, ds + " --results " + res.string()), "both");
    expect_error(run(SM_EVALUATE_EXE, ds + " --results " + res.string() + " --results-scale 0"), "results-scale");
  }
}

TEST_CASE("sm_calibrate: --save-rectified creates its folder, a failed run leaves nothing", "[unit][tools][cli]") {
  fs::create_directories(tmp_root());
  const fs::path base = tmp_root() / "calib";
  fs::remove_all(base);
  const fs::path boards = base / "boards", out = base / "out";
  sm::test::write_chessboard_rig(boards);
  fs::create_directories(out);
  const std::string o =
      boards.string() + " -o " + (out / "c.json").string() + " --yaml " + (out / "c.yaml").string() + " ";
  SECTION("success: JSON, YAML and one rectified image per pair in a new nested folder") {
    const Run r = run(SM_CALIBRATE_EXE, o + "--save-rectified " + (out / "rect" / "pairs").string());
    INFO(r.out << r.err);
    REQUIRE(r.rc == 0);
    CHECK(r.out.find("pairs used 9 of 9") != std::string::npos);
    expect_only(out, {"c.json", "c.yaml", "rect"});
    expect_only(out / "rect", {"pairs"});
    std::vector<std::string> pairs;
    for (int i = 0; i < 9; ++i) pairs.push_back(fmt::format("rectified_{:02d}.png", i));
    expect_only(out / "rect" / "pairs", pairs);
    for (const auto& f : pairs) {
      const cv::Mat m = cv::imread((out / "rect" / "pairs" / f).string(), cv::IMREAD_UNCHANGED);
      CHECK(m.size() == cv::Size(640, 240));  // left and right at 320x240, side by side
    }
    const sm::CalibFile c = sm::load_calib((out / "c.json").string());
    CHECK(c.width == 320);
    CHECK(c.rect_radius_needed >= 2);  // the roll needs rows above and below
    CHECK(c.rect_radius_needed <= sm::HwConfig{}.rect_radius);
  }
  SECTION("failures after the YAML and images were made leave no JSON, YAML, image or folder") {
    expect_error(run(SM_CALIBRATE_EXE, o + "--check-vdisp 0.000001 --save-rectified " + (out / "rect").string()),
                 "exceeds --check-vdisp");
    expect_only(out, {});
    expect_error(run(SM_CALIBRATE_EXE, o + "--rect-radius 1 --save-rectified " + (out / "rect").string()),
                 "the rig needs RECT_RADIUS >= ");
    expect_only(out, {});
    std::ofstream((out / "file").string()) << "x";
    expect_error(run(SM_CALIBRATE_EXE, o + "--save-rectified " + (out / "file" / "rect").string()), "is not a folder");
    expect_only(out, {"file"});
    expect_error(run(SM_CALIBRATE_EXE, boards.string() + " -o " + (out / "none" / "c.json").string() + " --yaml " +
                                           (out / "c.yaml").string()),
                 "c.json");
    expect_only(out, {"file"});
  }
}
