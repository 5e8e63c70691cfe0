// Shared tool helpers (toolio/sm_io.*): bad-1.0 metric on hand-computed cases,
// disparity renderings, disparity files, image loading errors and atomic writes.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "post.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_json_file.hpp"
#include "toolio/sm_object_flags.hpp"
#include "toolio/sm_regs_json.hpp"
#include "sm_test_util.hpp"

namespace fs = std::filesystem;
using namespace sm::tools;

namespace {
fs::path scratch(const std::string& name) { return sm::test::fresh_dir(fs::path(SM_TEST_TMP) / name); }

// A disparity file read back (`back`) against what was written (`f`, negative = invalid):
// CV_32FC1 of the same size, each invalid pixel (and with zero_invalid a 0) negative,
// every other pixel exact.
void check_read_back(const cv::Mat& back, const cv::Mat& f, bool zero_invalid) {
  REQUIRE(back.type() == CV_32FC1);
  REQUIRE(back.size() == f.size());
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x) {
      INFO("x " << x << " y " << y);
      const float w = f.at<float>(y, x);
      if (w < 0 || (zero_invalid && w == 0))
        CHECK(back.at<float>(y, x) < 0);
      else
        CHECK(back.at<float>(y, x) == w);
    }
}
}  // namespace

TEST_CASE("bad-1.0 on a hand-computed 4x2 case", "[unit][tools]") {
  // gt:  0 (unknown)  2.0  3.5  10       est: 5  3.0  2.4  -1 (invalid)
  //      4          4    4    4               4  5.5  2    4
  const cv::Mat gt = (cv::Mat_<float>(2, 4) << 0, 2.0f, 3.5f, 10, 4, 4, 4, 4);
  const cv::Mat est = (cv::Mat_<float>(2, 4) << 5, 3.0f, 2.4f, -1, 4, 5.5f, 2, 4);
  BadStats s = bad1(est, gt, cv::Mat());
  CHECK(s.evaluated == 7);  // the unknown pixel is skipped
  CHECK(s.invalid == 1);
  // bad: 3.5 vs 2.4 (1.1), invalid, 4 vs 5.5 (1.5), 4 vs 2 (2) -> 4; |1.0| is not bad.
  CHECK(s.bad == 4);
  CHECK(s.bad_pct() == Approx(400.0 / 7));
  const cv::Mat mask = (cv::Mat_<uint8_t>(2, 4) << 255, 255, 0, 0, 255, 255, 255, 255);
  s = bad1(est, gt, mask);
  CHECK(s.evaluated == 5);
  CHECK(s.bad == 2);
  CHECK(s.invalid == 0);
}

TEST_CASE("streak measure on a hand-built 12x10 case", "[unit][tools]") {
  // Ground truth 5 everywhere, except: (x=11, y=4) unknown, (10, 5) a one-row thin
  // structure at 8, (9, 2) at 6 (a step of exactly 1 is smooth); nonocc mask 0 at (0, 7).
  // Smooth pixels: rows 1..8 (96) minus (11, 3..5) [unknown neighbour], (10, 4..6)
  // [gt step of 3] and (0, 6..8) [masked neighbour] = 87.
  cv::Mat gt(10, 12, CV_32F, cv::Scalar(5.0f));
  gt.at<float>(4, 11) = 0;
  gt.at<float>(5, 10) = 8;
  gt.at<float>(2, 9) = 6;
  cv::Mat mask(10, 12, CV_8UC1, cv::Scalar(255));
  mask.at<uint8_t>(7, 0) = 0;
  cv::Mat est(10, 12, CV_32F, cv::Scalar(5.0f));
  // One-row streaks (7 pixels): a run of 4 in row 3; a sub-pixel spike 2.5 off; at x = 7
  // two wrong pixels around a right one (the right one differs from both but is not bad).
  for (int x = 0; x < 4; ++x) est.at<float>(3, x) = 9;
  est.at<float>(6, 6) = 7.5f;
  est.at<float>(4, 7) = 8;
  est.at<float>(6, 7) = 8;
  // Two rows thick (4 pixels), and (8, 2) below an invalid pixel with good pixels two
  // rows above and one below (the invalid row is inside the span: 2 rows).
  for (int y = 5; y < 7; ++y)
    for (int x = 4; x < 6; ++x) est.at<float>(y, x) = 9;
  est.at<float>(1, 8) = -1;
  est.at<float>(2, 8) = 9;
  // Three rows thick (3 pixels; the bounding good pixel below is in the last row).
  for (int y = 6; y < 9; ++y) est.at<float>(y, 3) = 9;
  // Never streaks: a difference of exactly 1, an invalid pixel, a wrong pixel in the first
  // row, and one-row streaks at pixels that are not smooth (unknown neighbour, masked
  // neighbour, gt step).
  est.at<float>(2, 6) = 6;
  est.at<float>(4, 8) = -1;
  est.at<float>(0, 5) = 9;
  est.at<float>(3, 11) = 9;
  est.at<float>(6, 0) = 9;
  est.at<float>(5, 10) = 12;
  StreakStats s = streaks(est, gt, mask);
  CHECK(s.smooth == 87);
  CHECK(s.streak == 7);
  CHECK(s.streak_pct() == Approx(700.0 / 87));
  CHECK(streaks(est, gt, mask, 2).streak == 7 + 4 + 1);
  CHECK(streaks(est, gt, mask, 3).streak == 7 + 4 + 1 + 3);
  CHECK(streaks(est, gt, mask, 8).streak == 15);
  CHECK(streaks(est, gt, mask, 3).smooth == 87);  // the denominator does not depend on the thickness
  // The denominator depends on the ground truth only; the truth itself has no streaks.
  CHECK(streaks(gt, gt, mask).smooth == 87);
  CHECK(streaks(gt, gt, mask, 8).streak == 0);
  // Without the mask, (0, 6..8) are smooth and (0, 6) is a streak.
  s = streaks(est, gt, cv::Mat());
  CHECK(s.smooth == 90);
  CHECK(s.streak == 8);
  // A whole wrong row is W streak pixels; the same two rows wrong are none of one row, and
  // 22 of two rows: (11, 3) is not smooth and (11, 2)'s span would reach the unknown (11, 4).
  cv::Mat row = gt.clone();
  row.row(2).setTo(20.0f);
  s = streaks(row, gt, mask);
  CHECK(s.smooth == 87);
  CHECK(s.streak == 12);  // every pixel of row 2 is smooth, (9, 2) with its gt 6 too
  row.row(3).setTo(20.0f);
  CHECK(streaks(row, gt, mask).streak == 0);
  CHECK(streaks(row, gt, mask, 2).streak == 22);
}

TEST_CASE("disparity renderings", "[unit][tools]") {
  sm::DispImage d(3, 1);
  d.at(0, 0) = sm::make_disp(0, true);
  d.at(1, 0) = sm::make_disp(15, true);
  d.at(2, 0) = sm::make_disp(7, false);
  const cv::Mat f = disp_to_float(d);
  CHECK(f.at<float>(0, 0) == 0.0f);
  CHECK(f.at<float>(0, 1) == 15.0f);
  CHECK(f.at<float>(0, 2) < 0.0f);
  // grey = 1 + round(d * 254 / (levels - 1)), invalid = 0: disparity 0 is grey 1
  const cv::Mat g = disp_to_grey(f, 16);
  CHECK(g.at<uint8_t>(0, 0) == 1);                                         // 1 + 0
  CHECK(g.at<uint8_t>(0, 1) == 255);                                       // 1 + 15 * 254 / 15
  CHECK(g.at<uint8_t>(0, 2) == 0);                                         // invalid
  const cv::Mat half = disp_to_grey((cv::Mat_<float>(1, 1) << 5.0f), 11);  // 1 + 5 * 254 / 10 = 1 + 127
  CHECK(half.at<uint8_t>(0, 0) == 128);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const cv::Mat m = disp_to_grey((cv::Mat_<float>(1, 6) << 1.0f, 7.0f, 20.0f, nan, inf, -inf), 16);
  CHECK(m.at<uint8_t>(0, 0) == 18);   // 1 + round(16.93)
  CHECK(m.at<uint8_t>(0, 1) == 120);  // 1 + round(7 * 254 / 15 = 118.53)
  CHECK(m.at<uint8_t>(0, 2) == 255);  // above levels - 1: clamped
  CHECK(m.at<uint8_t>(0, 3) == 0);    // NaN and infinities are invalid
  CHECK(m.at<uint8_t>(0, 4) == 0);
  CHECK(m.at<uint8_t>(0, 5) == 0);
  // colour: OpenCV's turbo map of grey 1 (disparity 0) and 255 (15), invalid and NaN black
  const cv::Mat c = disp_to_colour((cv::Mat_<float>(1, 4) << 0.0f, 15.0f, -1.0f, nan), 16);
  cv::Mat turbo;
  cv::applyColorMap(cv::Mat((cv::Mat_<uint8_t>(1, 2) << 1, 255)), turbo, cv::COLORMAP_TURBO);
  CHECK(c.type() == CV_8UC3);
  CHECK(c.at<cv::Vec3b>(0, 0) == turbo.at<cv::Vec3b>(0, 0));
  CHECK(c.at<cv::Vec3b>(0, 0) != cv::Vec3b(0, 0, 0));
  CHECK(c.at<cv::Vec3b>(0, 1) == turbo.at<cv::Vec3b>(0, 1));
  CHECK(c.at<cv::Vec3b>(0, 2) == cv::Vec3b(0, 0, 0));
  CHECK(c.at<cv::Vec3b>(0, 3) == cv::Vec3b(0, 0, 0));
}

TEST_CASE("image loading: colour to grey, errors name the file", "[unit][tools]") {
  const fs::path d = scratch("io_load");
  cv::Mat bgr(5, 7, CV_8UC3, cv::Scalar(10, 200, 60));
  REQUIRE(cv::imwrite((d / "c.png").string(), bgr));
  const sm::Image8 g = load_grey((d / "c.png").string());
  CHECK(g.w == 7);
  CHECK(g.h == 5);
  cv::Mat ref;
  cv::cvtColor(bgr, ref, cv::COLOR_BGR2GRAY);
  CHECK(g.at(3, 2) == ref.at<uint8_t>(2, 3));
  CHECK(to_mat(g).at<uint8_t>(4, 6) == ref.at<uint8_t>(4, 6));

  auto fails_with = [](const std::string& path, const std::string& what) {
    try {
      load_grey(path);
    } catch (const ToolError& e) {
      const std::string m = e.what();
      CHECK(m.find(path) != std::string::npos);
      CHECK(m.find(what) != std::string::npos);
      CHECK(m.find('\n') == std::string::npos);
      return true;
    }
    return false;
  };
  CHECK(fails_with((d / "missing.png").string(), "no such file"));
  { std::ofstream((d / "text.png").string()) << "not an image\n"; }
  CHECK(fails_with((d / "text.png").string(), "not a readable image"));
  {  // a PNG cut in the middle of its data
    std::vector<uchar> buf;
    cv::Mat noise(64, 64, CV_8UC1);
    cv::randu(noise, 0, 255);
    cv::imencode(".png", noise, buf);
    std::ofstream f((d / "trunc.png").string(), std::ios::binary);
    f.write(reinterpret_cast<const char*>(buf.data()), static_cast<std::streamsize>(buf.size() / 2));
  }
  CHECK(fails_with((d / "trunc.png").string(), "truncated"));
  { std::ofstream((d / "empty.png").string()); }
  CHECK(fails_with((d / "empty.png").string(), "empty"));
}

TEST_CASE("atomic writes leave the final file only", "[unit][tools]") {
  const fs::path d = scratch("io_write");
  write_image_atomic((d / "a.png").string(), cv::Mat(4, 4, CV_8UC1, cv::Scalar(7)));
  write_text_atomic((d / "t.txt").string(), "hello\n");
  int n = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    (void)e;
    ++n;
  }
  CHECK(n == 2);
  CHECK(cv::imread((d / "a.png").string(), cv::IMREAD_UNCHANGED).at<uint8_t>(3, 3) == 7);
  // Unwritable target: error, and nothing left behind.
  CHECK_THROWS_AS(write_image_atomic((d / "no_dir" / "x.png").string(), cv::Mat(4, 4, CV_8UC1)), ToolError);
  CHECK_THROWS_AS(write_image_atomic((d / "x.unknownext").string(), cv::Mat(4, 4, CV_8UC1)), ToolError);
  n = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    (void)e;
    ++n;
  }
  CHECK(n == 2);
}

TEST_CASE("dataset listing and scene errors", "[unit][tools]") {
  const fs::path d = scratch("io_dataset");
  CHECK_THROWS_AS(list_scenes((d / "nope").string()), ToolError);
  CHECK(list_scenes(d.string()).empty());
  fs::create_directories(d / "b");
  fs::create_directories(d / "a");
  fs::create_directories(d / "junk");
  cv::Mat img(20, 30, CV_8UC1, cv::Scalar(100));
  for (const char* s : {"a", "b"}) {
    cv::imwrite((d / s / "left.png").string(), img);
    cv::imwrite((d / s / "right.png").string(), img);
    cv::imwrite((d / s / "gt.png").string(), img);
    std::ofstream((d / s / "scale.txt").string()) << "4 60\n";
  }
  const auto scenes = list_scenes(d.string());
  REQUIRE(scenes.size() == 2);
  CHECK(fs::path(scenes[0]).filename() == "a");
  const Scene sc = load_scene(scenes[0]);
  CHECK(sc.name == "a");
  CHECK(sc.scale == 4);
  CHECK(sc.levels == 60);
  CHECK(sc.gt.at<float>(0, 0) == 25.0f);
  CHECK(sc.nonocc.empty());
  cv::imwrite((d / "b" / "right.png").string(), cv::Mat(20, 31, CV_8UC1));
  CHECK_THROWS_WITH(load_scene(scenes[1]), Catch::Contains("differ in size"));
  std::ofstream((d / "a" / "scale.txt").string()) << "four\n";
  CHECK_THROWS_WITH(load_scene(scenes[0]), Catch::Contains("scale.txt"));
}

TEST_CASE("disparity files: 16-bit PNG and PFM round trips", "[unit][tools]") {
  const fs::path d = scratch("io_disparity");
  // 5 x 3, every row different (a flipped PFM would not read back), invalid pixels and
  // a half-pixel value; disparity 0 is valid here.
  const cv::Mat f = (cv::Mat_<float>(3, 5) << 0, 1, 2.5f, -1, 127,  //
                     10, 11, 12, 13, -1,                            //
                     100, 0.0625f, 3, 4, 5);
  SECTION("16-bit PNG: d * 16, 0 = invalid") {
    const std::string p = (d / "disp.png").string();
    write_disparity_file(p, f);
    const cv::Mat raw = cv::imread(p, cv::IMREAD_UNCHANGED);
    REQUIRE(raw.type() == CV_16UC1);
    CHECK(raw.at<uint16_t>(0, 2) == 40);
    CHECK(raw.at<uint16_t>(0, 3) == 0);
    CHECK(raw.at<uint16_t>(0, 4) == 127 * 16);
    CHECK(raw.at<uint16_t>(2, 0) == 1600);
    CHECK(raw.at<uint16_t>(2, 1) == 1);
    // A valid disparity of exactly 0 is written as 0 and reads back as invalid (the
    // convention cannot tell them apart); every other value is exact.
    check_read_back(read_disparity_file(p), f, true);
    // Another scale (e.g. KITTI's 256) divides by it.
    CHECK(read_disparity_file(p, 256).at<float>(2, 0) == 6.25f);
  }
  SECTION("PFM: float, +infinity = invalid, rows stored bottom to top") {
    const std::string p = (d / "disp.pfm").string();
    write_disparity_file(p, f);
    {
      // The file itself: "Pf", width height, negative scale (little endian), then the
      // bottom row first.
      std::ifstream in(p, std::ios::binary);
      std::string magic;
      int w = 0, h = 0;
      double scale = 0;
      in >> magic >> w >> h >> scale;
      in.get();  // the single whitespace before the data
      CHECK(magic == "Pf");
      CHECK(w == 5);
      CHECK(h == 3);
      CHECK(scale < 0);
      std::vector<float> data(15);
      in.read(reinterpret_cast<char*>(data.data()), 15 * sizeof(float));
      REQUIRE(in);
      CHECK(data[0] == 100.0f);  // first stored row = image row 2
      CHECK(data[1] == 0.0625f);
      CHECK(std::isinf(data[2 * 5 + 3]));  // image row 0, column 3: invalid
      CHECK(data[2 * 5 + 3] > 0);
      CHECK(data[2 * 5 + 4] == 127.0f);
    }
    check_read_back(read_disparity_file(p), f, false);
  }
  SECTION("errors name the file") {
    CHECK_THROWS_WITH(write_disparity_file((d / "disp.tif").string(), f), Catch::Contains("disp.tif"));
    CHECK_THROWS_WITH(read_disparity_file((d / "none.pfm").string()), Catch::Contains("none.pfm"));
    CHECK_THROWS_WITH(read_disparity_file((d / "disp.jpg").string()), Catch::Contains("disp.jpg"));
    cv::imwrite((d / "colour.png").string(), cv::Mat(3, 3, CV_8UC3, cv::Scalar(1, 2, 3)));
    CHECK_THROWS_WITH(read_disparity_file((d / "colour.png").string()), Catch::Contains("colour.png"));
    // Unwritable target: nothing left behind.
    CHECK_THROWS_AS(write_disparity_file((d / "no_dir" / "x.pfm").string(), f), ToolError);
  }
}

TEST_CASE("register words, parameter fields and range errors have one definition", "[unit][tools]") {
  sm::HwConfig hw;
  // HwConfig::field: the member of an sm_top parameter name, as parameters() reports it
  REQUIRE(hw.field("DISP") == &hw.disp);
  *hw.field("BAND_K") = 4;
  CHECK(hw.band_k == 4);
  CHECK(hw.parameters().at("BAND_K") == 4);
  CHECK(hw.field("disp") == nullptr);
  for (const auto& [name, v] : hw.parameters()) CHECK(*hw.field(name) == v);

  // SW_TABLE words: codes 0 1 2 3 repeated -> 0xE4 a byte, in both the tools and the model
  sm::Regs r = sm::Regs::defaults(hw);
  for (size_t k = 0; k < r.sw_table.size(); ++k) r.sw_table[k] = static_cast<uint8_t>(k % 4);
  CHECK(sm::sw_table_word(r, 0) == 0xE4E4E4E4u);
  CHECK(register_value("SW_TABLE1", r) == 0xE4E4E4E4);
  set_register("SW_TABLE1", 0x0000001B, hw, r, "--sw-table1");  // codes 3 2 1 0, then 0
  CHECK(sm::sw_table_word(r, 1) == 0x1Bu);
  CHECK(r.sw_table[16] == 3);
  CHECK(r.sw_table[19] == 0);
  CHECK(sm::sw_table_word(r, 0) == 0xE4E4E4E4u);

  // one wording for an option and a register file key: what, value and range
  CHECK_THROWS_WITH(set_register("OCC", 256, hw, r, "--occ"), "--occ = 256 is outside 0..255");
  const fs::path d = scratch("regs_json");
  std::ofstream((d / "r.json").string()) << R"({"disp": 64, "occ": 256})";
  const std::string f = (d / "r.json").string();
  CHECK_THROWS_WITH(apply_regs_json(f, hw, r), f + ": 'occ' = 256 is outside 0..255");
  std::ofstream((d / "h.json").string()) << R"({"band_k": 99})";
  CHECK_THROWS_WITH(apply_regs_json((d / "h.json").string(), hw, r), Catch::Contains("'band_k' = 99 is outside"));
  std::ofstream((d / "u.json").string()) << R"({"OCC": 3})";
  CHECK_THROWS_WITH(apply_regs_json((d / "u.json").string(), hw, r), Catch::Contains("unknown key 'OCC'"));
  std::ofstream((d / "ok.json").string()) << R"({"sw_table1": 27, "disp": 64, "occ": 20})";
  const RegsFile rf = apply_regs_json((d / "ok.json").string(), hw, r);
  CHECK(rf.keys == std::vector<std::string>{"disp", "occ", "sw_table1"});
  CHECK(hw.disp == 64);
  CHECK(r.occ == 20);
  CHECK(sm::sw_table_word(r, 1) == 27u);
}

TEST_CASE("strict JSON files: one value, no key twice in one object", "[unit][tools]") {
  using sm::tools::parse_json_strict;
  // the same key in sibling objects, in objects of an array and at different depths is fine
  CHECK(parse_json_strict(R"({"a": {"x": 1}, "b": {"x": 2}, "x": [{"x": 1}, {"x": 2}]})", "f.json")["b"]["x"] == 2);
  CHECK(parse_json_strict("  [1, 2]\n\n", "f.json").size() == 2);
  CHECK_THROWS_WITH(parse_json_strict(R"({"occ": 5, "occ": 30})", "f.json"),
                    "f.json: key 'occ' given twice in one object");
  CHECK_THROWS_WITH(parse_json_strict(R"([{"a": {"y": 1, "y": 2}}])", "f.json"),
                    "f.json: key 'y' given twice in one object");
  // after a nested object closes, its keys no longer count for the outer one, and back
  CHECK_THROWS_WITH(parse_json_strict(R"({"k": {"k": 1}, "k": 2})", "f.json"),
                    "f.json: key 'k' given twice in one object");
  CHECK_THROWS_WITH(parse_json_strict("{\"occ\": 20} trailing", "f.json"),
                    "f.json: content after the JSON value on line 1 (one value per file)");
  CHECK_THROWS_WITH(parse_json_strict("{}\n{}\n", "f.json"),
                    "f.json: content after the JSON value on line 2 (one value per file)");
  CHECK_THROWS_WITH(parse_json_strict("", "f.json"), Catch::StartsWith("f.json: malformed JSON: "));
  CHECK_THROWS_WITH(parse_json_strict("{\"occ\": ", "f.json"), Catch::StartsWith("f.json: malformed JSON: "));
  const fs::path d = scratch("strict_json");
  CHECK_THROWS_WITH(sm::tools::read_json_file(d.string()), d.string() + ": is a directory");
  CHECK_THROWS_WITH(sm::tools::read_json_file((d / "none.json").string()), Catch::EndsWith("none.json: no such file"));
}

TEST_CASE("object flags: one explanation per flag, naming what to change", "[unit][tools]") {
  sm::HwConfig hw;
  hw.max_objects = 8;
  hw.label_slots = 64;
  sm::Regs regs = sm::Regs::defaults(hw);
  regs.obj_min_pixels = 64;
  sm::ObjectList l;
  CHECK(object_flag_lines(sm::object_packet(l, false)[0], hw, regs).empty());
  l.table_full = true;
  std::vector<std::string> s = object_flag_lines(sm::object_packet(l, false)[0], hw, regs);
  REQUIRE(s.size() == 1);
  CHECK(s[0].rfind("TABLE-FULL:", 0) == 0);
  CHECK(s[0].find("LABEL_SLOTS = 64") != std::string::npos);
  CHECK(s[0].find("OBJ_MIN_PIXELS = 64") != std::string::npos);
  l.table_full = false;
  l.too_many_objects = true;
  s = object_flag_lines(sm::object_packet(l, true)[0], hw, regs);
  REQUIRE(s.size() == 2);
  CHECK(s[0].rfind("TOO-MANY:", 0) == 0);
  CHECK(s[0].find("MAX_OBJECTS = 8") != std::string::npos);
  CHECK(s[1].rfind("LOST:", 0) == 0);
  CHECK(s[1].find("m_axis_obj_tready") != std::string::npos);
  CHECK(object_flag_lines(0xA5000700u, hw, regs).size() == 3);
}
