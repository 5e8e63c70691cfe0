// Bad inputs to the command-line tools, one test case per class of bad input (label
// robust, docs/robustness.md "Tools"): each asserts the exit code (1 a bad input or
// output, 2 a command line CLI11 cannot parse), the one error line "TOOL: error: ..."
// naming the file or option, and that no output file exists afterwards.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "toolio/sm_scenegen.hpp"
#include "sm_cmd.hpp"
#include "sm_tool_expect.hpp"
#include "sm_test_util.hpp"

namespace fs = std::filesystem;

namespace {

using Run = sm::test::CmdResult;

fs::path root() { return fs::path(SM_TEST_TMP) / "robust"; }

Run run(const std::string& exe, const std::string& args) { return sm::test::run_cmd(exe, args, root()); }

using sm::test::expect_empty;
using sm::test::expect_error;

void write(const fs::path& p, const std::string& text) { std::ofstream(p.string(), std::ios::binary) << text; }

// A small scene (64x48, 16 levels) and an empty output folder, fresh for every test case.
struct Fx {
  fs::path dir, scene, out;
  Fx() {
    dir = root() / "fx";
    fs::remove_all(dir);
    scene = dir / "scene";
    out = dir / "out";
    fs::create_directories(out);
    const auto p = sm::test::scene_params(64, 48, 16, 2, 3);
    sm::tools::write_scene(sm::tools::render_scene(p), p, scene.string());
  }
  std::string pair() const { return (scene / "left.png").string() + " " + (scene / "right.png").string(); }
  std::string file(const char* name, const std::string& text) const {
    write(dir / name, text);
    return (dir / name).string();
  }
  std::string o(const char* name) const { return (out / name).string(); }
};

// A real xc7 report from a minimal Yosys `stat -json` (3 LUT6, 2 FDRE), at fx.dir/name.
std::string xc7_report(const Fx& fx, const char* name) {
  const std::string stat =
      fx.file("stat.json", R"({"modules": {"\\top": {"num_cells_by_type": {"LUT6": 3, "FDRE": 2}}}})");
  const std::string out = (fx.dir / name).string();
  REQUIRE(
      run(SM_SYNTH_REPORT_EXE, "report --quiet --stat " + stat + " --top top --family xc7 --config c -o " + out).rc ==
      0);
  return out;
}

}  // namespace

TEST_CASE("JSON inputs: a key twice in one object", "[robust][tools]") {
  Fx fx;
  const std::string f = fx.file("dup.json", R"({"occ": 5, "occ": 30})");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --regs " + f), 1, "stereo_model",
               "dup.json: key 'occ' given twice in one object");
  // nested objects: the same key in two sibling objects is fine, twice in one is not
  const std::string n = fx.file("nested.json", R"({"modules": {"a": {"x": 1}, "b": {"x": 2, "x": 3}}})");
  expect_error(run(SM_REGMAP_GEN_EXE, n + " " + fx.out.string()), 1, "sm_regmap_gen",
               "nested.json: key 'x' given twice in one object");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --json " + fx.o("e.json") + " --regs " + f), 1, "sm_evaluate",
               "dup.json: key 'occ' given twice");
  expect_empty(fx.out);
}

TEST_CASE("JSON inputs: content after the value", "[robust][tools]") {
  Fx fx;
  for (const auto& [name, text] : std::vector<std::pair<const char*, const char*>>{
           {"trail.json", "{\"occ\": 20} trailing"}, {"two.json", "{\"occ\": 20}\n{\"occ\": 3}\n"}}) {
    const std::string f = fx.file(name, text);
    expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --regs " + f), 1, "stereo_model",
                 std::string(name) + ": content after the JSON value on line ");
    expect_error(run(SM_SYNTH_REPORT_EXE, "show " + f), 1, "sm_synth_report", name);
  }
  expect_empty(fx.out);
}

TEST_CASE("JSON inputs: a value of the wrong type names the key", "[robust][tools]") {
  Fx fx;
  const std::string f = fx.file("type.json", R"({"occ": "5"})");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --regs " + f), 1, "stereo_model",
               "type.json: 'occ' must be an integer, not \"5\"");
  expect_empty(fx.out);
}

TEST_CASE("JSON inputs: a number beyond 64 bits signed is reported as written", "[robust][tools]") {
  Fx fx;
  const std::string f = fx.file("big.json", R"({"occ": 18446744073709551615})");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --regs " + f), 1, "stereo_model",
               "big.json: 'occ' = 18446744073709551615 is outside 0..255");
  expect_empty(fx.out);
}

TEST_CASE("input files that are folders", "[robust][tools]") {
  Fx fx;
  const std::string d = fx.dir.string();
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --regs " + d), 1, "stereo_model",
               d + ": is a directory");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --calib " + d), 1, "stereo_model",
               d + ": is a directory");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --json " + fx.o("e.json") + " --regs " + d), 1, "sm_evaluate",
               d + ": is a directory");
  expect_error(run(SM_SYNTH_REPORT_EXE, "combine --top t --family f --config c -o " + fx.o("r.json") + " " + d), 1,
               "sm_synth_report", d + ": is a directory");
  expect_empty(fx.out);
}

TEST_CASE("outputs that cannot be written are refused before any work", "[robust][tools]") {
  Fx fx;
  const std::string nodir = (fx.out / "nodir" / "x.json").string();
  const std::string file = fx.file("plain", "x");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --levels 0 --methods bm --json " + nodir), 1, "sm_evaluate",
               "--json " + nodir + ": cannot write: folder ");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --levels 0 --methods bm --json " + file + "/x.json"), 1,
               "sm_evaluate", "is not a folder");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --levels 0 --methods bm --disp-images " + file), 1,
               "sm_evaluate", "--disp-images " + file + ": cannot write: not a folder");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " --disp-file " + (fx.out / "no" / "d.pfm").string()), 1,
               "stereo_model", "--disp-file " + (fx.out / "no" / "d.pfm").string() + ": cannot write: folder");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.out.string()), 1, "stereo_model",
               "cannot write: is a folder");
  expect_error(run(SM_SCENE_EXE, "--out " + file + "/s"), 1, "sm_scene", "--out " + file + "/s: cannot write");
  // a folder still to be made is named, not only the ancestor that refuses it
  expect_error(run(SM_SCENE_EXE, "--out /proc/sm_no/s"), 1, "sm_scene", "cannot create /proc/sm_no/s in /proc");
  // sm_coverage: an unwritable second output, or a bad input, leaves no first output either
  const std::string dat = fx.file("c.dat", "# SystemC::Coverage-3\n");
  expect_error(run(SM_COVERAGE_EXE, dat + " --json " + fx.o("c.json") + " --line-dat " + nodir), 1, "sm_coverage",
               "--line-dat " + nodir + ": cannot write");
  expect_error(run(SM_COVERAGE_EXE, dat + " --json " + dat), 1, "sm_coverage", ": same file as the input");
  CHECK(sm::test::slurp(dat) == "# SystemC::Coverage-3\n");
  expect_error(run(SM_COVERAGE_EXE, dat + " --json " + fx.out.string()), 1, "sm_coverage", "cannot write: is a folder");
  const std::string bad = fx.file("bad.dat", "# SystemC::Coverage-3\nC 'x' 5x\n");
  expect_error(run(SM_COVERAGE_EXE, bad + " --json " + fx.o("c.json")), 1, "sm_coverage", "bad.dat:2: bad count");
  // no progress line: the evaluation never started
  CHECK(run(SM_EVALUATE_EXE, fx.scene.string() + " --levels 0 --methods bm --json " + nodir).err.find("[1/") ==
        std::string::npos);
  expect_empty(fx.out);
}

TEST_CASE("two outputs naming the same file", "[robust][tools]") {
  Fx fx;
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --colour " + fx.o("d.png")), 1,
               "stereo_model", "--colour " + fx.o("d.png") + ": same file as -o");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " --disp-file " + fx.o("d.png") + " --objects-json " +
                                            (fx.out / "." / "d.png").string()),
               1, "stereo_model", "same file as --disp-file");
  // an output that would replace an input
  const std::string left = (fx.scene / "left.png").string();
  const auto size = fs::file_size(left);
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + left), 1, "stereo_model",
               "-o " + left + ": same file as the input left " + left);
  CHECK(fs::file_size(left) == size);
  // a results file and a pictures folder of one name
  expect_error(run(SM_EVALUATE_EXE,
                   fx.scene.string() + " --levels 0 --methods bm --json " + fx.o("r") + " --disp-images " + fx.o("r")),
               1, "sm_evaluate", "--disp-images " + fx.o("r") + ": same path as --json");
  expect_empty(fx.out);
}

TEST_CASE("numbers on the command line: non-finite, out of range, not a number", "[robust][tools]") {
  Fx fx;
  const std::string s = "--out " + fx.o("scene");
  expect_error(run(SM_SCENE_EXE, s + " --rot-deg inf"), 2, "sm_scene", "--rot-deg: inf: not a finite number");
  expect_error(run(SM_SCENE_EXE, s + " --noise nan"), 2, "sm_scene", "--noise: nan: not a finite number");
  expect_error(run(SM_SCENE_EXE, s + " --seed -1"), 2, "sm_scene", "--seed: -1: outside 0..");
  expect_error(run(SM_SCENE_EXE, s + " --gain-r abc"), 2, "sm_scene", "--gain-r: 'abc': not a number");
  expect_error(run(SM_EVALUATE_EXE, "--synthetic -1"), 2, "sm_evaluate", "--synthetic: -1: outside 1..1000");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --results-scale nan"), 2, "sm_evaluate",
               "--results-scale: nan: not a finite number");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --occ abc"), 2, "sm_evaluate",
               "--occ: 'abc': not an integer in 0..255");
  expect_error(run(SM_EVALUATE_EXE, "--synthetic 1 --synthetic-size 320x240x5"), 1, "sm_evaluate",
               "--synthetic-size 320x240x5: expected WxH");
  const std::string dat = fx.file("c.dat", "# SystemC::Coverage-3\n");
  const Run c = run(SM_COVERAGE_EXE, dat + " --line-min 0");
  expect_error(c, 2, "sm_coverage", "--line-min: 0: outside 1..");
  CHECK(c.err.size() < 100);  // no 300-digit bound
  expect_error(run(SM_COVERAGE_EXE, dat + " --goal-line nan"), 2, "sm_coverage", "--goal-line: nan");
  expect_error(
      run(SM_SYNTH_REPORT_EXE, "report --stat x --top t --family f --config c -o " + fx.o("r.json") + " --seconds inf"),
      2, "sm_synth_report", "--seconds: inf: not a finite number");
  // range checks made after the parse exit as the parser's do
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " --threads 0 -o " + fx.o("d.png")), 2, "stereo_model",
               "--threads: 0: outside 1..256");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --threads 300"), 2, "sm_evaluate",
               "--threads: 300: outside 1..256");
  // an sm_top parameter's own range (rtl/defs.json) is the option's; combinations stay exit 1
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " --disp 0 -o " + fx.o("d.png")), 2, "stereo_model",
               "--disp: 0: must be even, 4..254");
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " --census 4 -o " + fx.o("d.png")), 2, "stereo_model",
               "--census: 4: must be odd, 3..15");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --levels 7"), 2, "sm_evaluate", "--levels 7: must be");
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --peer-levels 17"), 2, "sm_evaluate",
               "--peer-levels 17: must be");
  expect_error(run(SM_EVALUATE_EXE, "--synthetic 1 --synthetic-size 40x30"), 2, "sm_evaluate",
               "--synthetic-size 40x30: 128 levels need at least 67 columns");
  expect_empty(fx.out);
}

TEST_CASE("bench_scale_dataset: all scenes or none", "[robust][tools]") {
  Fx fx;
  const fs::path ds = fx.dir / "ds";
  fs::create_directories(ds);
  fs::copy(fx.scene, ds / "a");
  fs::copy(fx.scene, ds / "b");
  cv::imwrite((ds / "b" / "right.png").string(), cv::Mat(20, 20, CV_8UC1, cv::Scalar(9)));  // the second is bad
  expect_error(run(SM_SCALE_DATASET_EXE, ds.string() + " --width 32 --height 24 --out " + fx.o("s")), 1,
               "bench_scale_dataset", "ds/b: left 64x48 and right 20x20 differ in size");
  expect_error(run(SM_SCALE_DATASET_EXE, ds.string() + " --out /proc/sm_no"), 1, "bench_scale_dataset",
               "--out /proc/sm_no: cannot write: cannot create /proc/sm_no in /proc");
  expect_error(run(SM_SCALE_DATASET_EXE, ds.string() + " --out o --width 4096"), 2, "bench_scale_dataset",
               "--width: 4096: outside 16..4095");
  expect_empty(fx.out);
}

TEST_CASE("inputs that exclude each other", "[robust][tools]") {
  Fx fx;
  expect_error(run(SM_EVALUATE_EXE, fx.scene.string() + " --synthetic 1 --json " + fx.o("e.json")), 2, "sm_evaluate",
               "excludes");
  expect_empty(fx.out);
}

TEST_CASE("command-line errors: one prefixed line, exit 2; --help exits 0", "[robust][tools]") {
  Fx fx;
  const std::string dat = fx.file("c.dat", "# SystemC::Coverage-3\n");
  // each tool with its required arguments, and an option it does not have
  const std::vector<std::tuple<std::string, std::string, std::string>> tools = {
      {SM_SCENE_EXE, "sm_scene", "--out " + fx.o("s")},
      {SM_STEREO_MODEL_EXE, "stereo_model", fx.pair() + " -o " + fx.o("d.png")},
      {SM_EVALUATE_EXE, "sm_evaluate", fx.scene.string()},
      {SM_COVERAGE_EXE, "sm_coverage", dat},
      {SM_SYNTH_REPORT_EXE, "sm_synth_report", "show " + dat},
      {SM_REGMAP_GEN_EXE, "sm_regmap_gen", dat + " " + fx.out.string()},
      {SM_OUTPUT_STUDY_EXE, "sm_output_study", fx.scene.string()}};
  for (const auto& [exe, name, args] : tools) {
    INFO(name);
    expect_error(run(exe, args + " --no-such-option"), 2, name, "--no-such-option");
    const Run h = run(exe, "--help");
    CHECK(h.rc == 0);
    CHECK(h.err.empty());
    CHECK(h.out.find("--help") != std::string::npos);
  }
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --occ"), 2, "stereo_model", "--occ");
  expect_error(run(SM_SCENE_EXE, ""), 2, "sm_scene", "--out is required");
  expect_empty(fx.out);
}

TEST_CASE("stereo_model: the register file's active size and --objects-json alone", "[robust][tools]") {
  Fx fx;
  const std::string f = fx.file("w.json", R"({"width": 40, "disp": 16})");
  const Run r = run(SM_STEREO_MODEL_EXE, fx.pair() + " --disp-file " + fx.o("d.png") + " --regs " + f);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("resized to the active size 40x48") != std::string::npos);  // said, not silent
  const cv::Mat d = cv::imread(fx.o("d.png"), cv::IMREAD_UNCHANGED);
  CHECK(d.cols == 40);
  CHECK(d.rows == 48);
  const Run j = run(SM_STEREO_MODEL_EXE, fx.pair() + " --disp 16 --objects-json " + fx.o("o.json"));
  INFO(j.err);
  REQUIRE(j.rc == 0);
  CHECK(nlohmann::json::parse(sm::test::slurp(fx.out / "o.json")).contains("objects"));
  // a width outside the register's range: the file, the key and the range
  const std::string bad = fx.file("w0.json", R"({"width": 5000})");
  fs::remove_all(fx.out);
  fs::create_directories(fx.out);
  expect_error(run(SM_STEREO_MODEL_EXE, fx.pair() + " -o " + fx.o("d.png") + " --regs " + bad), 1, "stereo_model",
               "w0.json: 'width' = 5000 is outside");
  expect_empty(fx.out);
}

TEST_CASE("sm_synth_report: reports whose keys have the wrong type", "[robust][tools]") {
  Fx fx;
  const std::string good = xc7_report(fx, "good.json");
  const nlohmann::json r = nlohmann::json::parse(sm::test::slurp(good));
  for (const auto& [key, value, shown] : std::vector<std::tuple<std::string, nlohmann::json, std::string>>{
           {"seconds", "fast", "'seconds' must be a number"},
           {"total", 5, "'total' must be an object"},
           {"blocks", nlohmann::json::array({1}), "'blocks' must be an object"},
           {"config", 7, "'config' must be a string"}}) {
    INFO(key);
    nlohmann::json bad = r;
    bad[key] = value;
    const std::string f = fx.file("bad.json", bad.dump());
    expect_error(run(SM_SYNTH_REPORT_EXE, "show " + f), 1, "sm_synth_report", "bad.json: " + shown);
    expect_error(run(SM_SYNTH_REPORT_EXE, "combine --top t --family f --config c -o " + fx.o("sum.json") + " " + f), 1,
                 "sm_synth_report", "bad.json: " + shown);
  }
  // a Yosys stat file with a count of the wrong type: the file named, no report
  const std::string bad_stat =
      fx.file("bad_stat.json", R"({"modules": {"\\top": {"num_cells_by_type": {"LUT6": "3"}}}})");
  expect_error(run(SM_SYNTH_REPORT_EXE,
                   "report --quiet --stat " + bad_stat + " --top top --family xc7 --config c -o " + fx.o("r.json")),
               1, "sm_synth_report", "bad_stat.json: unexpected Yosys JSON: type must be number");
  // a part's instance count: digits only
  expect_error(
      run(SM_SYNTH_REPORT_EXE, "combine --top t --family f --config c -o " + fx.o("sum.json") + " " + good + "@x"), 1,
      "sm_synth_report", "@x: bad instance count 'x'");
  nlohmann::json bad = r;
  bad["total"]["luts"] = "many";
  expect_error(run(SM_SYNTH_REPORT_EXE, "show " + fx.file("bad.json", bad.dump())), 1, "sm_synth_report",
               "'total.luts' must be an integer");
  expect_empty(fx.out);
}

// A minimal nextpnr-ecp5 --report: one clock, the cells used, a path of a flip-flop, two
// logic cells (0.4 ns, 0.3 ns) and routing (1.0 ns, 0.5 ns).
std::string nextpnr_report(double fmax, int comb) {
  const auto cell = [](const char* c) { return nlohmann::json{{"cell", c}, {"loc", {1, 1}}, {"port", "Q"}}; };
  const auto step = [&](const char* type, double d, const char* c) {
    return nlohmann::json{{"type", type}, {"delay", d}, {"from", cell(c)}, {"to", cell(c)}};
  };
  nlohmann::json r = {
      {"fmax", {{"aclk", {{"achieved", fmax}, {"constraint", 100}}}}},
      {"utilization",
       {{"TRELLIS_COMB", {{"used", comb}, {"available", 83640}}}, {"DP16KD", {{"used", 2}, {"available", 208}}}}},
      {"critical_paths",
       {{{"from", "posedge aclk"},
         {"to", "posedge aclk"},
         {"path",
          {step("clk-to-q", 0.5, "a_q"), step("routing", 1.0, "a_q"), step("logic", 0.4, "lut1"),
           step("routing", 0.5, "lut1"), step("logic", 0.3, "lut2"), step("setup", 0.1, "b_q")}}}}}};
  return r.dump();
}

TEST_CASE("sm_synth_report pnr: nextpnr's report read, blocks summed, bad files refused", "[robust][tools]") {
  Fx fx;
  const std::string a = fx.o("a.json"), b = fx.o("b.json"), sum = fx.o("sum.json");
  const auto pnr = [&](const std::string& in, const char* top, const std::string& out) {
    return run(SM_SYNTH_REPORT_EXE,
               fmt::format("pnr --quiet --nextpnr {} --top {} --config c --device d -o {}", in, top, out));
  };
  REQUIRE(pnr(fx.file("pa.json", nextpnr_report(80.0, 100)), "sm_a", a).rc == 0);
  REQUIRE(pnr(fx.file("pb.json", nextpnr_report(50.0, 30)), "sm_b", b).rc == 0);
  const auto ra = nlohmann::json::parse(sm::test::slurp(a));
  CHECK(ra["family"] == "ecp5");
  CHECK(ra["total"]["fmax_mhz"] == 80.0);
  CHECK(ra["total"]["comb"] == 100);
  CHECK(ra["total"]["ebr"] == 2);
  CHECK(ra["total"]["path_cells"] == 2);
  CHECK(ra["total"]["path_logic_ns"].get<double>() == Approx(0.5 + 0.4 + 0.3 + 0.1));
  CHECK(ra["total"]["path_routing_ns"].get<double>() == Approx(1.5));
  CHECK(ra["total"]["path_from"] == "a_q");
  CHECK(ra["total"]["path_to"] == "b_q");
  // the sum: cells times instances, the slowest block's clock
  const Run s = run(SM_SYNTH_REPORT_EXE, "combine --top t --family ecp5 --config c -o " + sum + " " + a + "@3 " + b);
  REQUIRE(s.rc == 0);
  const auto rs = nlohmann::json::parse(sm::test::slurp(sum));
  CHECK(rs["total"]["comb"] == 3 * 100 + 30);
  CHECK(rs["total"]["ebr"] == 4 * 2);
  CHECK(rs["total"]["fmax_mhz"] == 50.0);
  CHECK(rs["total"]["slowest_block"] == "sm_b");
  CHECK(rs["blocks"]["sm_a"]["instances"] == 3);
  const Run shown = run(SM_SYNTH_REPORT_EXE, "show " + sum);
  CHECK(shown.rc == 0);
  CHECK(shown.out.find("Fmax 50.0 MHz (target 100), slowest block sm_b") != std::string::npos);
  // not a nextpnr report; an xc7 report in an ecp5 sum
  fs::remove_all(fx.out);
  fs::create_directories(fx.out);
  expect_error(pnr(fx.file("np.json", R"({"fmax": {}})"), "sm_a", fx.o("x.json")), 1, "sm_synth_report",
               "np.json: not a nextpnr report");
  const std::string xc7 = xc7_report(fx, "xc7.json");
  expect_error(run(SM_SYNTH_REPORT_EXE, "combine --top t --family ecp5 --config c -o " + sum + " " + xc7), 1,
               "sm_synth_report", "xc7.json: not a report of family ecp5");
  expect_empty(fx.out);
}

TEST_CASE("sm_output_study: refused before any work", "[robust][tools]") {
  Fx fx;
  const std::string file = fx.file("f", "x");
  expect_error(run(SM_OUTPUT_STUDY_EXE, fx.scene.string() + " --dump-features " + file), 1, "sm_output_study",
               "--dump-features " + file + ": cannot write: not a folder");
  expect_error(run(SM_OUTPUT_STUDY_EXE, fx.scene.string() + " --study bound"), 1, "sm_output_study",
               "--study bound: needs two scenes or more");
  expect_error(run(SM_OUTPUT_STUDY_EXE, fx.scene.string() + " --scenes nosuch"), 1, "sm_output_study",
               "--scenes: nosuch: not a scene of");
  expect_error(run(SM_OUTPUT_STUDY_EXE, fx.scene.string() + " --study foo"), 2, "sm_output_study", "--study: foo");
  expect_error(run(SM_OUTPUT_STUDY_EXE, fx.scene.string() + " --levels 7"), 2, "sm_output_study",
               "--levels 7: must be 0 (per scene) or even, 4..254");
  expect_empty(fx.out);
}
