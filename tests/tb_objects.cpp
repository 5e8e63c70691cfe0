// Block test of sm_objects (docs/algorithm.md, section 8): frames of box scenes, random
// and blocky disparity maps, merging shapes, overflow cases, label recycling and invalid
// pixels, back to back with random
// ce gaps and garbage on idle/virtual beats and on the register inputs outside the
// frame's first beat. Every published list (read through the read port) and every
// AXI4-Stream packet is compared with the model; a packet is held back over three
// publications, so three lists are published while it is pending and two are scanned
// beside it (the lost case, and the list banks' rotation around the packet's). The last
// list's packet is held across a reset of rst_n alone (a soft reset): it must finish
// unchanged, and the list read back is empty. The published list is read again on every
// clock until the next one replaces it, one object a clock, so a scan that wrote into it
// would be seen.
#include <fmt/format.h>

#include <deque>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "post.hpp"
#include "sm_block_test.hpp"

using namespace sm;
using namespace sm::test;

namespace {
struct Box {
  int x0, y0, x1, y1;
  unsigned d;
};
DispImage box_scene(int w, int h, unsigned bg, const std::vector<Box>& boxes) {
  DispImage m(w, h, make_disp(bg, true));
  for (const Box& b : boxes)
    for (int y = b.y0; y <= std::min(b.y1, h - 1); ++y)
      for (int x = b.x0; x <= std::min(b.x1, w - 1); ++x) m.at(x, y) = make_disp(b.d, true);
  return m;
}
DispImage random_map(std::mt19937& rng, int w, int h, int disp, int block) {
  DispImage m(w, h);
  const int bw = (w + block - 1) / block, bh = (h + block - 1) / block;
  std::vector<DispPix> cells(static_cast<size_t>(bw) * bh);
  for (auto& c : cells) {
    const bool valid = rng() % 10 != 0;
    c = make_disp(valid ? rng() % disp : rng() & 0x7fff, valid);
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      DispPix p = cells[static_cast<size_t>(y / block) * bw + x / block];
      if (block > 1 && rng() % 8 == 0 && disp_valid(p))  // jitter inside the tolerance
        p = make_disp(std::min<unsigned>(disp - 1, disp_value(p) + 1), true);
      m.at(x, y) = p;
    }
  return m;
}
// Combs: arms of random heights and widths standing on a bar, an arm flat at the comb's
// base depth or jittered, the bar a sawtooth from the base up, all inside the tolerance.
// The arms get labels of their own and merge where they reach the bar, in every order:
// the absorbed label taller or shorter, left or right of the survivor, its maximum above
// or below the survivor's and below the joining pixel's (a bar label deeper than a flat
// arm, meeting it on a rising tooth).
DispImage comb_scene(std::mt19937& rng, int w, int h, unsigned D, unsigned tol) {
  DispImage m(w, h, make_disp(1, true));
  for (int k = 0; k < 6; ++k) {
    const int len = 4 + static_cast<int>(rng() % 14);
    const int xa = static_cast<int>(rng() % static_cast<unsigned>(std::max(1, w - len)));
    const int yb = 3 + static_cast<int>(rng() % static_cast<unsigned>(h - 3));
    const unsigned base = D / 2 + 2 + rng() % std::max(1u, D / 2 - 3 - tol);
    auto put = [&](int x, int y, unsigned d) {
      if (x < w && y < h) m.at(x, y) = make_disp(std::min(D - 1, d), true);
    };
    for (int x = xa; x < xa + len; ++x) put(x, yb, base + static_cast<unsigned>(x - xa) % (tol + 1));
    const int arms = 2 + static_cast<int>(rng() % 3);
    for (int a = 0; a < arms; ++a) {
      const int ax = xa + static_cast<int>(rng() % static_cast<unsigned>(len));
      const int top = static_cast<int>(rng() % static_cast<unsigned>(yb));
      const int aw = 1 + static_cast<int>(rng() % 2);
      const bool jitter = rng() % 2 != 0;
      const unsigned arm_d = base;
      for (int y = top; y < yb; ++y)
        for (int x = ax; x < ax + aw; ++x) put(x, y, jitter ? base + static_cast<unsigned>(rng() % (tol + 1)) : arm_d);
    }
  }
  return m;
}
}  // namespace

int main(int argc, char** argv) {
  const HwConfig hw = verilated_config();
  BlockTest<SM_VTOP> t{"sm_objects block test"};
  int w = 37, h = 23;
  // room for the scenes' boxes
  t.option("--width", w, "active width").range(16, hw.max_width);
  t.option("--height", h, "rows of every frame").range(7, hw.max_height);
  if (auto rc = t.parse(argc, argv)) return *rc;
  const unsigned D = hw.disp;
  std::mt19937 rng(4321);

  std::vector<DispImage> in;
  std::vector<Regs> regs;
  auto add = [&](DispImage m, unsigned near, unsigned tol, unsigned minpix) {
    Regs r = Regs::defaults(hw);
    r.width = w;
    r.height = h;
    r.obj_near = static_cast<uint8_t>(near);
    r.obj_tol = static_cast<uint8_t>(tol);
    r.obj_min_pixels = static_cast<uint16_t>(minpix);
    in.push_back(std::move(m));
    regs.push_back(r);
  };
  // 0: three boxes at known depths on a far background
  add(box_scene(
          w, h, 2,
          {{2, 2, w / 4, h / 3, D / 2 + 2}, {w / 3, h / 2, w / 2, h - 3, D - 3}, {w - 9, 1, w - 2, h - 2, D / 2 + 5}}),
      D / 2, 1, 4);
  // 1: random map: many components, overflows the table and the list
  add(random_map(rng, w, h, D, 1), D / 2, 2, 0);
  // 2: more boxes than MAX_OBJECTS, plus specks below min_pixels
  {
    std::vector<Box> b;
    for (int i = 0; i < hw.max_objects + 2; ++i)
      b.push_back({(i * 4) % (w - 3), 1 + (i * 4 / (w - 3)) * 5, (i * 4) % (w - 3) + 2, 3 + (i * 4 / (w - 3)) * 5,
                   D - 1 - static_cast<unsigned>(i % 3)});
    b.push_back({w - 2, h - 2, w - 1, h - 1, D - 1});
    add(box_scene(w, h, 0, b), D / 4, 0, 5);
  }
  // 3: blocky random map (merges across blocks within the tolerance)
  add(random_map(rng, w, h, D, 4), D / 3, 3, 6);
  // 4: a U and a comb: labels that meet only further down must merge
  {
    DispImage m(w, h, make_disp(1, true));
    for (int y = 2; y < h - 2; ++y) {
      m.at(3, y) = m.at(4, y) = m.at(12, y) = make_disp(D - 2, true);
      if (y == h - 3)
        for (int x = 3; x <= 12; ++x) m.at(x, y) = make_disp(D - 2, true);
    }
    for (int x = 15; x < w - 1; ++x) m.at(x, h - 2) = make_disp(D - 4, true);
    for (int x = 15; x < w - 1; x += 2)
      for (int y = 1; y < h - 2; ++y) m.at(x, y) = make_disp(D - 4 + (y % 3 == 0), true);
    add(m, D / 2, 1, 1);
  }
  // 5: boxes again with a different threshold, and a random blocky map after it
  add(box_scene(w, h, D / 4, {{5, 5, w - 6, h - 6, D / 2}, {8, 8, 12, 12, D - 1}}), D / 3, 4, 1);
  add(random_map(rng, w, h, D, 3), D / 2, 1, 3);
  // 7, 8: register extremes (every bit of the latched threshold, tolerance and minimum
  // size set, then cleared): nothing is near; then everything is, no component is large enough
  add(random_map(rng, w, h, D, 2), 255, 255, 0xffff);
  add(random_map(rng, w, h, D, 2), 0, 128, 0x8000);
  // 9..11: combs (merge shapes) at three tolerances
  for (unsigned tol = 1; tol <= 3; ++tol) add(comb_scene(rng, w, h, D, tol), D / 2, tol, 1);
  // 12: two U's whose absorbed arm (the younger label) holds the object's deepest pixel,
  // rising a step per row and back before the bar joins it: the merge must take the
  // absorbed label's maximum, not the survivor's or the joining pixel's. Left U: both
  // arms start on one row, the right arm is younger; right U: the right arm starts a row
  // higher, the left arm is younger. (They need 22 columns.)
  if (w >= 22) {
    DispImage m(w, h, make_disp(1, true));
    const unsigned base = D / 2, peak = 4;
    const int yb = h - 3;
    auto arm = [&](int x, int top, bool rises) {
      for (int y = top; y < yb; ++y) {
        const unsigned up = static_cast<unsigned>(std::min({y - top, yb - 1 - y, static_cast<int>(peak)}));
        m.at(x, y) = make_disp(base + (rises ? up : 0), true);
      }
    };
    for (const auto& [x0, left_rises] : {std::pair<int, bool>{2, false}, std::pair<int, bool>{14, true}}) {
      arm(x0, 2, left_rises);
      arm(x0 + 7, left_rises ? 1 : 2, !left_rises);
      for (int x = x0; x <= x0 + 7; ++x) m.at(x, yb) = make_disp(base, true);
    }
    add(m, D / 2, 1, 1);
  }

  // 13: label recycling, components that ended below min_pixels: rows of single-pixel
  // specks (more in all than LABEL_SLOTS, fewer per row), then a box that needs a label
  const size_t f_specks = in.size();
  {
    DispImage m(w, h, make_disp(1, true));
    const int per_row = std::min(w / 3, hw.label_slots - 2);
    for (int y = 0; y <= 4; y += 2)
      for (int i = 0; i < per_row; ++i) m.at(3 * i + y / 2 % 2, y) = make_disp(D - 3, true);
    for (int y = 7; y < h - 1; ++y)
      for (int x = 4; x < 10; ++x) m.at(x, y) = make_disp(D - 2 - static_cast<unsigned>(y % 2), true);
    add(m, D / 2, 1, 2);
  }
  // 14: label recycling, absorbed labels: a staircase whose rows each start one pixel
  // further left, with a new label that the component above absorbs a pixel later
  const size_t f_stairs = in.size();
  {
    DispImage m(w, h, make_disp(1, true));
    for (int y = 1; y < h - 1; ++y)
      for (int x = w - 2 - y; x < w - 1; ++x) m.at(x, y) = make_disp(D - 2 - static_cast<unsigned>(x % 2), true);
    add(m, D / 2, 1, 2);
  }
  // 15: invalid pixels whose disparity bits are near are never objects: an invalid box,
  // and a valid box cut in two by an invalid column
  const size_t f_invalid = in.size();
  {
    DispImage m(w, h, make_disp(1, true));
    for (int y = 2; y < h - 2; ++y)
      for (int x = 2; x < w - 2; ++x) m.at(x, y) = make_disp(D - 1, x >= w / 2 && x != w / 2 + 3);
    add(m, D / 2, 1, 1);
  }

  std::vector<ObjectList> want;
  for (size_t f = 0; f < in.size(); ++f) want.push_back(separate_objects(in[f], regs[f], hw));
  // The model's lists of the directed frames (independent of the RTL): the recycling
  // leaves room for every component, and the invalid pixels count for nothing.
  auto expect = [&](size_t f, size_t n, const char* what) {
    if (want[f].table_full || want[f].objects.size() != n)
      t.fail(fmt::format("frame {} ({}): the model lists {} objects, table_full {}; expected {}, no table_full", f,
                         what, want[f].objects.size(), want[f].table_full, n));
  };
  expect(f_specks, 1, "specks, then a box");
  expect(f_stairs, 1, "staircase");
  expect(f_invalid, 2, "invalid pixels");
  if (want[f_stairs].objects.size() == 1 &&
      want[f_stairs].objects[0].count != static_cast<uint32_t>((h - 2) * (h + 1) / 2))
    t.fail(fmt::format("frame {} (staircase): {} pixels counted", f_stairs, want[f_stairs].objects[0].count));
  if (want[f_invalid].objects.size() == 2 && want[f_invalid].objects[0].count + want[f_invalid].objects[1].count !=
                                                 static_cast<uint32_t>((h - 4) * (w - 2 - w / 2 - 1)))
    t.fail(fmt::format("frame {} (invalid pixels): valid pixels miscounted", f_invalid));

  const std::vector<int> heights(in.size(), h);
  const auto sched = make_schedule(w, heights, 2);

  auto& tb = t.tb();
  tb->out_rst_n = 0;
  tb->ce = 1;
  tb->width = w;
  tb->height = h;
  tb->s_side = 0;
  tb->m_axis_obj_tready = 0;
  t.reset(3);
  tb->out_rst_n = 1;

  t.ce_schedule(99, 30);
  auto fail = [&](const std::string& msg) { t.fail(msg); };
  auto read_object = [&](size_t i) {
    tb->rd_index = static_cast<uint8_t>(i);
    tb->eval();
    Object g;
    g.x0 = tb->rd_x0;
    g.y0 = tb->rd_y0;
    g.x1 = tb->rd_x1;
    g.y1 = tb->rd_y1;
    g.count = tb->rd_count;
    g.sum_disp = tb->rd_sum;
    g.mean_disp = tb->rd_mean;
    g.max_disp = tb->rd_max;
    return g;
  };
  const ObjectList* shown = nullptr;  // the published list
  size_t reread = 0, reread_bad = 0;
  bool soft_reset_done = false;
  size_t k = 0, lists = 0;
  bool lost_pending = false;
  std::deque<std::vector<uint32_t>> want_pkts;
  std::vector<uint32_t> cur_pkt;
  size_t pkts = 0;
  long idle = 0;
  while (k < sched.size() || lists < in.size() || !want_pkts.empty()) {
    if (k >= sched.size() && ++idle > 100000) {
      fail("timeout waiting for lists/packets");
      break;
    }
    // hold the packet of list 2 until list 5 is published (the packets of lists 3..5 are
    // lost), and the last list's packet until a soft reset has passed
    const bool last_held = lists == in.size() && !soft_reset_done;
    if (last_held && tb->m_axis_obj_tvalid) {
      // a soft reset while the last list's packet waits (rst_n alone; out_rst_n stays high)
      tb->m_axis_obj_tready = 0;
      t.reset(3, [&] { tb->ce = rng() & 1; });
      tb->ce = 0;
      tb->eval();
      if (tb->obj_count != 0 || !tb->m_axis_obj_tvalid) fail("soft reset: the list is not empty or the packet stopped");
      soft_reset_done = true;
      shown = nullptr;
      continue;
    }
    const bool c = k < sched.size() && t.next_ce();
    if (!c) tb->ce = 0;
    tb->near_thr = rng() & 0xff;
    tb->tol = rng() & 0xff;
    tb->min_pixels = rng() & 0xffff;
    if (c) {
      const BeatInfo& b = sched[k++];
      tb->s_side = b.side;
      tb->s_disp = b.frame >= 0 ? in[b.frame].at(b.x, b.y) : static_cast<uint16_t>(rng());
      if (b.frame >= 0 && b.x == 0 && b.y == 0) {
        tb->near_thr = regs[b.frame].obj_near;
        tb->tol = regs[b.frame].obj_tol;
        tb->min_pixels = regs[b.frame].obj_min_pixels;
      }
    } else {
      tb->s_side = rng() & 31;
      tb->s_disp = static_cast<uint16_t>(rng());
    }
    tb->m_axis_obj_tready = ((lists >= 3 && lists <= 5) || last_held) ? 0 : (rng() % 3 != 0);
    if (shown && !shown->objects.empty()) {
      const size_t i = reread++ % shown->objects.size();
      if (!(read_object(i) == shown->objects[i]) && reread_bad++ == 0)
        fail(fmt::format("list {} object {} changed before the next list was published", lists - 1, i));
    }
    tb->eval();
    const bool tvalid_pre = tb->m_axis_obj_tvalid;
    if (tb->m_axis_obj_tvalid && tb->m_axis_obj_tready) {
      cur_pkt.push_back(tb->m_axis_obj_tdata);
      if (tb->m_axis_obj_tlast) {
        if (want_pkts.empty()) {
          fail(fmt::format("unexpected packet {}", pkts));
        } else {
          if (cur_pkt != want_pkts.front()) {
            std::string msg = fmt::format("packet {}: words", pkts);
            for (size_t i = 0; i < std::max(cur_pkt.size(), want_pkts.front().size()); ++i)
              msg += fmt::format(" {:08x}/{:08x}", i < want_pkts.front().size() ? want_pkts.front()[i] : 0u,
                                 i < cur_pkt.size() ? cur_pkt[i] : 0u);
            fail(msg + " (expected/got)");
          } else {
            t.pass();
          }
          want_pkts.pop_front();
        }
        ++pkts;
        cur_pkt.clear();
      }
    }
    tb.tick();
    if (tb->list_ready) {
      if (lists >= in.size()) {
        fail("more lists than frames");
        break;
      }
      const ObjectList& e = want[lists];
      const int f = static_cast<int>(lists);
      if (tb->obj_count != e.objects.size() || tb->too_many != e.too_many_objects || tb->table_full != e.table_full)
        fail(fmt::format("frame {}: count/too_many/table_full expected {}/{}/{} got {}/{}/{}", f, e.objects.size(),
                         e.too_many_objects, e.table_full, tb->obj_count, tb->too_many, tb->table_full));
      else
        t.pass();
      for (size_t i = 0; i < e.objects.size() && i < tb->obj_count; ++i) {
        const Object& o = e.objects[i];
        const Object g = read_object(i);
        if (!(g == o))
          fail(
              fmt::format("frame {} object {}: expected box ({},{})-({},{}) n {} sum {} mean {} "
                          "max {}, got ({},{})-({},{}) n {} sum {} mean {} max {}",
                          f, i, o.x0, o.y0, o.x1, o.y1, o.count, o.sum_disp, o.mean_disp, o.max_disp, g.x0, g.y0, g.x1,
                          g.y1, g.count, g.sum_disp, g.mean_disp, g.max_disp));
        else
          t.pass();
      }
      if (f == 0 || f == 2 || f == 5 || f >= static_cast<int>(f_specks))
        fmt::print("frame {}: {} objects, too_many {}, table_full {}\n", f, e.objects.size(), e.too_many_objects,
                   e.table_full);
      // the packet engine was busy at publication: this list's packet is dropped
      if (tvalid_pre) {
        lost_pending = true;
      } else {
        want_pkts.push_back(object_packet(e, lost_pending));
        lost_pending = false;
      }
      if (tb->pkt_lost != lost_pending) fail(fmt::format("frame {}: pkt_lost flag", f));
      shown = &e;
      ++lists;
    }
  }
  bool saw_flags[3] = {false, false, false};
  for (const auto& e : want) {
    saw_flags[0] |= e.too_many_objects;
    saw_flags[1] |= e.table_full;
  }
  saw_flags[2] = pkts + 3 == in.size() && soft_reset_done;
  if (reread_bad == 0) t.pass();
  if (!saw_flags[0] || !saw_flags[1] || !saw_flags[2])
    fail(fmt::format("coverage: too_many {} table_full {} three lost packets and a soft reset {}", saw_flags[0],
                     saw_flags[1], saw_flags[2]));
  return t.finish(fmt::format("tb_objects {} lists, {} packets, {} reads of a published list", lists, pkts, reread));
}
