// Model tests of the post-processing (docs/algorithm.md sections 7-8) against
// independent truth: hand-computed cases, OpenCV's medianBlur and connectedComponents.
#include <algorithm>
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <tuple>

#include "post.hpp"

using namespace sm;

namespace {
HwConfig small_hw() {
  HwConfig hw;
  hw.max_width = 64;
  hw.max_height = 64;
  hw.disp = 64;
  hw.max_objects = 4;
  hw.label_slots = 16;
  return hw;
}
DispImage constant(int w, int h, unsigned d) { return DispImage(w, h, make_disp(d, true)); }

// The register defaults with the object separation's three registers set.
Regs object_regs(const HwConfig& hw, uint8_t near, uint8_t tol, uint16_t min_pixels) {
  Regs regs = Regs::defaults(hw);
  regs.obj_near = near;
  regs.obj_tol = tol;
  regs.obj_min_pixels = min_pixels;
  return regs;
}
}  // namespace

TEST_CASE("vertical median removes one- and two-row streaks", "[unit][post]") {
  const HwConfig hw = small_hw();
  DispImage m = constant(20, 12, 10);
  for (int x = 3; x < 15; ++x) m.at(x, 4) = make_disp(40, true);             // one row
  for (int x = 2; x < 9; ++x) m.at(x, 8) = m.at(x, 9) = make_disp(3, true);  // two rows
  CHECK(post_vmedian(m, hw) == constant(20, 12, 10));
  // a three-row band is a real surface and stays
  DispImage band = constant(20, 12, 10);
  for (int y = 4; y < 7; ++y)
    for (int x = 0; x < 20; ++x) band.at(x, y) = make_disp(30, true);
  CHECK(post_vmedian(band, hw) == band);
}

TEST_CASE("3x3 median equals cv::medianBlur on the interior", "[unit][post]") {
  const HwConfig hw = small_hw();
  std::mt19937 rng(5);
  DispImage m(40, 30);
  cv::Mat keys(30, 40, CV_8U);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const unsigned d = rng() % 64;
      m.at(x, y) = make_disp(d, true);
      keys.at<uint8_t>(y, x) = static_cast<uint8_t>(d);
    }
  cv::Mat ref;
  cv::medianBlur(keys, ref, 3);
  const DispImage out = post_median3(m, hw);
  for (int y = 1; y < 29; ++y)
    for (int x = 1; x < 39; ++x) {
      INFO("x " << x << " y " << y);
      REQUIRE(out.at(x, y) == make_disp(ref.at<uint8_t>(y, x), true));
    }
}

TEST_CASE("median window hand cases: border rule, invalid pixels, 1x5 and 5x3 windows", "[unit][post]") {
  const HwConfig hw = small_hw();
  // horizontal 1x5 at x=2 of the row 1 5 2 9 3 -> sorted 1 2 3 5 9 -> 3
  DispImage r(5, 1);
  const unsigned v[5] = {1, 5, 2, 9, 3};
  for (int x = 0; x < 5; ++x) r.at(x, 0) = make_disp(v[x], true);
  const DispImage h = post_median(r, hw, 0, 2);
  CHECK(h.at(2, 0) == make_disp(3, true));
  // x=0: window 1 1 1 5 2 (two outside pixels take the centre 1) -> 1
  CHECK(h.at(0, 0) == make_disp(1, true));
  // x=4: 2 9 3 3 3 -> 3
  CHECK(h.at(4, 0) == make_disp(3, true));
  // invalid pixels sort lowest: 3 of 5 invalid -> invalid (0x0000)
  DispImage c(1, 5, make_disp(7, true));
  c.at(0, 1) = make_disp(9, false);
  c.at(0, 2) = 0;
  c.at(0, 3) = make_disp(1, false);
  const DispImage vm = post_vmedian(c, hw);
  CHECK(vm.at(0, 2) == 0);
  // at y=0 the window is 7 7 7 inv inv (two outside rows take the centre) -> 7
  CHECK(vm.at(0, 0) == make_disp(7, true));
  // 5x3 window at the centre of a 5x3 image holding 0..14 -> 7; at its corner (0,0) the
  // window is 0 1 / 3 4 / 6 7 inside plus 9 copies of the centre 0 -> 0
  DispImage g(3, 5);
  for (int i = 0; i < 15; ++i) g.at(i % 3, i / 3) = make_disp(i, true);
  const DispImage gm = post_median53(g, hw);
  CHECK(gm.at(1, 2) == make_disp(7, true));
  CHECK(gm.at(0, 0) == make_disp(0, true));
  // (2,4) holds 14: inside 7 8 10 11 13 14, 9 outside copies of 14 -> 14
  CHECK(gm.at(2, 4) == make_disp(14, true));
  // (1,3) holds 10: inside rows 1..4 x cols 0..2 = 3..14 (12 values) + 3 copies of 10
  // -> sorted 3..9 (7 values), then 10 10 10 10: the 8th (index 7) is 10
  CHECK(gm.at(1, 3) == make_disp(10, true));
  // an isolated wrong pixel vanishes under the 3x3 median
  DispImage s = constant(7, 7, 20);
  s.at(3, 3) = make_disp(50, true);
  CHECK(post_median3(s, hw) == constant(7, 7, 20));
}

TEST_CASE("post_process follows filter_enable and reports every step", "[unit][post]") {
  const HwConfig hw = small_hw();
  std::mt19937 rng(9);
  DispImage m(25, 15);
  for (auto& p : m.px) p = make_disp(rng() % 64, rng() % 8 != 0);
  Regs regs = Regs::defaults(hw);
  std::vector<DispImage> steps;
  CHECK(regs.filter_enable == 15);  // every filter on by default
  regs.filter_enable = 0;
  CHECK(post_process(m, regs, hw, &steps) == m);
  REQUIRE(steps.size() == 4);
  regs.filter_enable = 2;
  CHECK(post_process(m, regs, hw) == post_median3(m, hw));
  regs.filter_enable = 7;
  const DispImage all = post_process(m, regs, hw, &steps);
  CHECK(steps[0] == m);
  CHECK(steps[1] == post_vmedian(m, hw));
  CHECK(steps[2] == post_median3(steps[1], hw));
  CHECK(all == post_median53(steps[2], hw));
  // F0 (bit 3) runs first, with the hardware's look-ahead
  regs.filter_enable = 8;
  CHECK(post_process(m, regs, hw) == post_band(m, hw, hw.band_k));
  REQUIRE(post_band(m, hw, hw.band_k) != post_band(m, hw, 1));  // band_k matters on this map
  regs.filter_enable = 9;
  CHECK(post_process(m, regs, hw) == post_vmedian(post_band(m, hw, hw.band_k), hw));
  regs.filter_enable = 15;
  const DispImage every = post_process(m, regs, hw, &steps);
  REQUIRE(steps.size() == 4);
  CHECK(steps[0] == post_band(m, hw, hw.band_k));
  CHECK(every == post_median53(post_median3(post_vmedian(steps[0], hw), hw), hw));
}

TEST_CASE("objects: boxes at known depths on a far background", "[unit][objects]") {
  const HwConfig hw = small_hw();
  Regs regs = object_regs(hw, 20, 1, 4);  // near, tol, min pixels
  DispImage m = constant(50, 40, 5);
  auto box = [&](int x0, int y0, int x1, int y1, unsigned d) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) m.at(x, y) = make_disp(d, true);
  };
  box(30, 3, 45, 10, 40);  // first in raster order (row 3)
  box(2, 12, 11, 30, 25);
  box(20, 20, 22, 22, 60);              // 9 pixels
  box(40, 38, 41, 38, 50);              // 2 pixels: below min_pixels
  m.at(16, 16) = make_disp(63, false);  // invalid: ignored
  const ObjectList l = separate_objects(m, regs, hw);
  REQUIRE(l.objects.size() == 3);
  CHECK_FALSE(l.too_many_objects);
  CHECK_FALSE(l.table_full);
  const Object& a = l.objects[0];
  CHECK((a.x0 == 30 && a.y0 == 3 && a.x1 == 45 && a.y1 == 10));
  CHECK(a.count == 16 * 8);
  CHECK(a.mean_disp == 40);
  CHECK(a.max_disp == 40);
  CHECK(a.sum_disp == 40 * 128);
  const Object& b = l.objects[1];
  CHECK((b.x0 == 2 && b.y0 == 12 && b.x1 == 11 && b.y1 == 30 && b.count == 190));
  CHECK(b.mean_disp == 25);
  const Object& c = l.objects[2];
  CHECK((c.x0 == 20 && c.y0 == 20 && c.x1 == 22 && c.y1 == 22 && c.count == 9));
  CHECK(c.mean_disp == 60);
}

TEST_CASE("objects: tolerance, merging shapes, mean and nearest disparity", "[unit][objects]") {
  const HwConfig hw = small_hw();
  Regs regs = object_regs(hw, 10, 2, 1);  // near, tol, min pixels
  // two touching halves at 30 and 32 merge (|dd| = 2); at 30 and 33 they do not
  DispImage m = constant(20, 10, 0);
  for (int y = 2; y < 6; ++y)
    for (int x = 2; x < 12; ++x) m.at(x, y) = make_disp(x < 7 ? 30 : 32, true);
  ObjectList l = separate_objects(m, regs, hw);
  REQUIRE(l.objects.size() == 1);
  CHECK(l.objects[0].count == 40);
  CHECK(l.objects[0].sum_disp == 20 * 30 + 20 * 32);
  CHECK(l.objects[0].mean_disp == 31);
  CHECK(l.objects[0].max_disp == 32);
  for (int y = 2; y < 6; ++y) m.at(11, y) = make_disp(35, true);
  l = separate_objects(m, regs, hw);
  CHECK(l.objects.size() == 2);
  // mean is floor: 3 pixels 30, 30, 31 -> 91 / 3 = 30
  DispImage t = constant(10, 3, 0);
  t.at(1, 1) = t.at(2, 1) = make_disp(30, true);
  t.at(3, 1) = make_disp(31, true);
  l = separate_objects(t, regs, hw);
  REQUIRE(l.objects.size() == 1);
  CHECK(l.objects[0].mean_disp == 30);
  // a U (arms meet only at the bottom) and a W are one object each
  DispImage u = constant(30, 12, 0);
  for (int y = 1; y < 10; ++y) u.at(2, y) = u.at(8, y) = make_disp(40, true);
  for (int x = 2; x <= 8; ++x) u.at(x, 9) = make_disp(40, true);
  for (int y = 1; y < 10; ++y) u.at(12, y) = u.at(16, y) = u.at(20, y) = make_disp(50, true);
  for (int x = 12; x <= 20; ++x) u.at(x, 10) = make_disp(50, true);
  u.at(12, 10) = u.at(12, 9);
  l = separate_objects(u, regs, hw);
  REQUIRE(l.objects.size() == 2);
  CHECK(l.objects[0].count == 9 + 9 + 5);
  CHECK((l.objects[1].x0 == 12 && l.objects[1].x1 == 20 && l.objects[1].y1 == 10));
  CHECK(l.objects[1].count == 27 + 9);
}

TEST_CASE("objects: overflow of the list and of the label table raise the flags", "[unit][objects]") {
  const HwConfig hw = small_hw();         // K = 4, 16 labels
  Regs regs = object_regs(hw, 10, 0, 2);  // near, tol, min pixels
  DispImage m = constant(40, 10, 0);
  for (int i = 0; i < 6; ++i) m.at(2 + 5 * i, 3) = m.at(3 + 5 * i, 3) = make_disp(20 + i, true);
  ObjectList l = separate_objects(m, regs, hw);
  CHECK(l.objects.size() == 4);
  CHECK(l.too_many_objects);
  CHECK_FALSE(l.table_full);
  CHECK(l.objects[3].mean_disp == 23);  // the first four in raster order
  // 20 isolated near pixels (singletons) then a big box: the box finds no label
  DispImage s = constant(40, 20, 0);
  for (int i = 0; i < 20; ++i) s.at(2 * i, 0) = make_disp(30, true);
  for (int y = 5; y < 15; ++y)
    for (int x = 5; x < 15; ++x) s.at(x, y) = make_disp(30, true);
  regs.obj_min_pixels = 1;
  l = separate_objects(s, regs, hw);
  CHECK(l.table_full);
  CHECK(l.too_many_objects);
  for (const Object& o : l.objects) CHECK(o.count == 1);  // the box was dropped
  // 20 components of the same row on 16 labels: the row itself overflows whatever the
  // minimum size (none of them has ended when the table fills)
  regs.obj_min_pixels = 2;
  l = separate_objects(s, regs, hw);
  CHECK(l.table_full);
  REQUIRE(l.objects.size() == 1);  // the box: the specks freed their labels once they ended
  CHECK(l.objects[0].count == 100);
}

TEST_CASE("objects: labels are recycled within the frame", "[unit][objects]") {
  const HwConfig hw = small_hw();         // K = 4, 16 labels
  Regs regs = object_regs(hw, 10, 0, 2);  // near, tol, min pixels
  // 12 single-pixel specks on each of rows 0, 2 and 4 (36 components on 16 labels), then a
  // box: each speck has ended two rows later and is below min_pixels, so its label is free
  // again and nothing overflows
  DispImage s = constant(40, 20, 0);
  for (int y = 0; y <= 4; y += 2)
    for (int i = 0; i < 12; ++i) s.at(3 * i, y) = make_disp(30, true);
  for (int y = 8; y < 18; ++y)
    for (int x = 5; x < 15; ++x) s.at(x, y) = make_disp(30, true);
  ObjectList l = separate_objects(s, regs, hw);
  CHECK_FALSE(l.table_full);
  REQUIRE(l.objects.size() == 1);
  CHECK((l.objects[0].x0 == 5 && l.objects[0].y0 == 8 && l.objects[0].x1 == 14 && l.objects[0].y1 == 17));
  CHECK(l.objects[0].count == 100);
  // specks that qualify (min_pixels 1) are objects and keep their labels: the box overflows
  regs.obj_min_pixels = 1;
  l = separate_objects(s, regs, hw);
  CHECK(l.table_full);
  CHECK(l.too_many_objects);
  // A disc's upper half: each row starts one pixel further left, with a label of its own
  // that the row above's component absorbs a pixel later (40 such labels, on 16). Absorbed
  // labels are recycled: one object, every pixel counted.
  DispImage t = constant(60, 44, 0);
  long n = 0;
  for (int y = 1; y <= 41; ++y)
    for (int x = 50 - y; x <= 55; ++x, ++n) t.at(x, y) = make_disp(40 + (y % 2), true);
  regs = object_regs(hw, 10, 1, 2);
  l = separate_objects(t, regs, hw);
  CHECK_FALSE(l.table_full);
  REQUIRE(l.objects.size() == 1);
  CHECK(l.objects[0].count == n);
  CHECK((l.objects[0].x0 == 9 && l.objects[0].y0 == 1 && l.objects[0].x1 == 55 && l.objects[0].y1 == 41));
  CHECK(l.objects[0].max_disp == 41);
}

TEST_CASE("objects: invalid pixels are never near, whatever their disparity bits", "[unit][objects]") {
  const HwConfig hw = small_hw();
  const Regs regs = object_regs(hw, 10, 1, 1);
  DispImage m = constant(30, 12, 0);
  for (int y = 2; y < 10; ++y)
    for (int x = 2; x < 28; ++x) m.at(x, y) = make_disp(40, x != 15);  // column 15 invalid (d bits 40)
  for (int y = 2; y < 10; ++y) m.at(15, y) = make_disp(40, false);
  ObjectList l = separate_objects(m, regs, hw);
  REQUIRE(l.objects.size() == 2);  // the invalid column splits the box
  CHECK((l.objects[0].x1 == 14 && l.objects[1].x0 == 16));
  CHECK(l.objects[0].count + l.objects[1].count == 8 * 25);
  DispImage inv(30, 12, make_disp(50, false));  // every pixel invalid with d = 50 >= near
  l = separate_objects(inv, regs, hw);
  CHECK(l.objects.empty());
  CHECK_FALSE(l.table_full);
}

// Random masks against OpenCV: with a table large enough never to recycle (every
// component listed, 45 % of the pixels near), and with 64 labels, a sparser mask and a
// minimum size of 5, where over 100 components start per frame and the ones below the
// minimum and the absorbed labels are recycled.
TEST_CASE("objects: components match cv::connectedComponentsWithStats", "[unit][objects]") {
  for (const auto& [slots, min_pixels, density] : {std::tuple<int, int, unsigned>{1024, 1, 45}, {64, 5, 30}}) {
    HwConfig hw = small_hw();
    hw.label_slots = slots;
    hw.max_objects = 1000;                                                        // model only: list every component
    const Regs regs = object_regs(hw, 10, 0, static_cast<uint16_t>(min_pixels));  // near, tol, min pixels
    std::mt19937 rng(17);
    for (int trial = 0; trial < 5; ++trial) {
      DispImage m(48, 32, make_disp(0, true));
      cv::Mat mask(32, 48, CV_8U, cv::Scalar(0));
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 48; ++x)
          if (rng() % 100 < density) {
            m.at(x, y) = make_disp(33, true);
            mask.at<uint8_t>(y, x) = 255;
          }
      cv::Mat lab, stats, cent;
      const int n = cv::connectedComponentsWithStats(mask, lab, stats, cent, 4, CV_32S);
      const ObjectList l = separate_objects(m, regs, hw);
      CHECK_FALSE(l.table_full);
      std::vector<std::array<int, 5>> a, b;
      for (int i = 1; i < n; ++i)
        if (stats.at<int>(i, cv::CC_STAT_AREA) >= min_pixels)
          a.push_back({stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                       stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT),
                       stats.at<int>(i, cv::CC_STAT_AREA)});
      for (const Object& o : l.objects)
        b.push_back({o.x0, o.y0, o.x1 - o.x0 + 1, o.y1 - o.y0 + 1, static_cast<int>(o.count)});
      CHECK(n > 100);  // more components than the small table holds
      CHECK_FALSE(l.too_many_objects);
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      CHECK(a == b);
    }
  }
}

TEST_CASE("object packet format", "[unit][objects]") {
  ObjectList l;
  const Object o{3, 4, 10, 12, 72, 2880, 40, 41};  // box x0 y0 x1 y1, count, sum, mean, nearest
  l.objects.push_back(o);
  l.table_full = true;
  const std::vector<uint32_t> p = object_packet(l, true);
  const std::vector<uint32_t> want = {0xA5000601u, 0x00040003u, 0x000C000Au, 72u, 2880u, 0x2928u};
  CHECK(p == want);
  CHECK(object_packet(ObjectList{}, false) == std::vector<uint32_t>{0xA5000000u});
}

TEST_CASE("band filter: hand-computed columns", "[unit][post]") {
  const HwConfig hw = small_hw();  // DISP 64: disparity bits 5:0
  // One column per case, rows top to bottom ('-' = invalid 7).
  const std::vector<std::vector<int>> in = {
      {5, 5, 9, 9, 5, 5, 5, 5},     // 0: two-row band between rows of 5 -> all 5 (k >= 2)
      {5, 5, 20, 20, 20, 5, 5, 5},  // 1: three-row band: kept at k = 2, replaced at k = 3
      {5, 5, 6, 6, 9, 6, 5, 5},     // 2: 6 is within 1 of 5 (kept); row 4: a = 6, row 5 = 6 -> 6
      {5, 5, 9, 9, 6, 9, 9, 9},     // 3: returns to 6 (within 1 of a = 5): rows 2, 3 -> 5
      {5, 5, 9, -1, 5, 9, 9, 9},    // 4: the invalid row never agrees; row 2 -> 5 (row 4);
                                    //    row 3 invalid stays; rows 5.. never return
      {5, 5, 5, 5, 5, 5, 9, 9},     // 5: a band at the bottom has no row to return to
      {9, 5, 5, 5, 5, 5, 5, 5},     // 6: row 0 passes unchanged
  };
  const int w = static_cast<int>(in.size()), h = 8;
  DispImage m(w, h);
  for (int x = 0; x < w; ++x)
    for (int y = 0; y < h; ++y) m.at(x, y) = in[x][y] < 0 ? make_disp(7, false) : make_disp(in[x][y], true);
  auto col = [&](const DispImage& o, int x) {
    std::vector<int> c;
    for (int y = 0; y < h; ++y) c.push_back(disp_valid(o.at(x, y)) ? static_cast<int>(disp_value(o.at(x, y))) : -1);
    return c;
  };
  const DispImage k2 = post_band(m, hw, 2), k3 = post_band(m, hw, 3), k1 = post_band(m, hw, 1);
  CHECK(col(k2, 0) == std::vector<int>{5, 5, 5, 5, 5, 5, 5, 5});
  CHECK(col(k1, 0) == std::vector<int>{5, 5, 9, 9, 5, 5, 5, 5});  // row 2: row 3 is 9 -> kept
  CHECK(col(k2, 1) == in[1]);
  CHECK(col(k3, 1) == std::vector<int>{5, 5, 5, 5, 5, 5, 5, 5});
  CHECK(col(k2, 2) == std::vector<int>{5, 5, 6, 6, 6, 6, 5, 5});
  CHECK(col(k2, 3) == std::vector<int>{5, 5, 5, 5, 6, 9, 9, 9});
  CHECK(col(k2, 4) == std::vector<int>{5, 5, 5, -1, 5, 9, 9, 9});
  CHECK(k2.at(4, 3) == 0);  // an invalid output is exactly 0x0000, like the medians'
  CHECK(col(k3, 5) == in[5]);
  CHECK(col(k3, 6) == in[6]);
  DispImage norm = m;
  norm.at(4, 3) = 0;
  CHECK(post_band(m, hw, 0) == norm);
  // the replacement is the output word above; bits above the disparity bits are dropped
  CHECK(k2.at(0, 2) == k2.at(0, 1));
  DispImage hi = m;
  hi.at(0, 1) = static_cast<DispPix>(make_disp(5, true) | 0x40);  // bit 6: above DISP 64's bits
  CHECK(post_band(hi, hw, 2).at(0, 1) == make_disp(5, true));
  CHECK(post_band(hi, hw, 2).at(0, 2) == make_disp(5, true));
}
