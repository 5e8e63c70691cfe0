// Block test of sm_cost against the model's matching_cost, at the scale sm_cost outputs
// it (C = cost >> COST_SHIFT, the bits the aggregation reads). The census inputs come from
// the model's census images of random image pairs (the right image a shifted copy of
// the left with noise, so low costs occur), the centre pixels from the images; virtual
// beats and idle cycles carry garbage. Every level of every real output pixel is compared. Folded (SM_P_PU defined,
// F = DISP / PU > 1): ce comes at most once every F clocks and the next beat's input
// (real or garbage) is held from the clock after a ce until its own ce, as sm_top
// guarantees; at F = 1 idle clocks carry garbage. --max-cost-frame appends a frame whose
// left image has isolated peaks (census code all ones) over a flat right image (all zeros),
// so the popcount trees reach their widest sums (and the intensity term, 155 >> AD_SHIFT,
// goes past CB: the cap).
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "census.hpp"
#include "sm_block_test.hpp"
#include "sm_port.hpp"

namespace {

constexpr int kMaxWidth = SM_P_MAX_WIDTH;
constexpr int kCensus = SM_P_CENSUS;
constexpr int kDisp = SM_P_DISP;

sm::CensusVec garbage(std::mt19937& rng) {
  auto w = [&] { return (static_cast<uint64_t>(rng()) << 32) | rng(); };
  return {w(), w(), w(), w()};
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_cost block test"};
  int w = 37;
  std::vector<int> heights = {9, 3, 5};
  t.option("--width", w, "active width").range(1, kMaxWidth);
  t.option("--heights", heights, "rows of each frame, sent back to back");
  bool max_cost_frame = false;
  t.flag("--max-cost-frame", max_cost_frame,
         "append a frame of isolated peaks over a flat right image (largest costs)");
  if (auto rc = t.parse(argc, argv)) return *rc;
  if (max_cost_frame) heights.push_back(heights.empty() ? kCensus : heights.back());
  const sm::HwConfig hw = sm::verilated_config();
  const int pu = hw.levels_per_clock();
  if (kDisp % pu != 0) {
    fmt::print(stderr, "tb_cost: PU {} does not divide DISP {}\n", pu, kDisp);
    return 2;
  }
  const int fold = kDisp / pu;  // clocks per beat
  const int cb = hw.census_bits();
  const int cw = hw.cost_bits();  // C's planes

  std::mt19937 rng(4321);
  std::vector<sm::Image8> left, right;
  std::vector<sm::CensusImage> cl, cr;
  std::vector<sm::CostVolume> cost;
  for (size_t f = 0; f < heights.size(); ++f) {
    const int h = heights[f];
    const int shift = static_cast<int>(3 + 5 * f) % kDisp;
    sm::Image8 l(w, h), r(w, h);
    if (max_cost_frame && f + 1 == heights.size()) {
      // A peak every CENSUS pixels is brighter than its whole window: left code all ones;
      // the flat right image's codes are all zeros, so the peak costs CB at every level.
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const bool peak = x % kCensus == kCensus / 2 && y % kCensus == kCensus / 2;
          l.at(x, y) = peak ? 255 : static_cast<uint8_t>(rng() % 200);
          r.at(x, y) = 100;
        }
    } else {
      for (auto& p : l.px) p = static_cast<uint8_t>(rng());
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          r.at(x, y) = (x + shift < w && rng() % 8) ? l.at(x + shift, y) : static_cast<uint8_t>(rng());
    }
    left.push_back(l);
    right.push_back(r);
    cl.push_back(sm::census_transform(l, hw));
    cr.push_back(sm::census_transform(r, hw));
    cost.push_back(sm::matching_cost(cl.back(), cr.back(), l, r, hw));
    if (max_cost_frame && f + 1 == heights.size()) {
      const auto& v = cost.back().v;
      const long at_cb = std::count(v.begin(), v.end(), static_cast<uint8_t>(cb));
      t.check(at_cb > 0, "the max-cost frame has no cost at CB");
      fmt::print("max-cost frame: {} costs at CB = {}\n", at_cb, cb);
    }
  }
  const auto sched = sm::test::make_schedule(w, heights, 1);

  t.ce_schedule(0xc057u, 30, fold);
  t.expect_frames(w, heights);
  t->width = w;
  t->ce = 1;
  t->s_side = 0;
  t.reset(3);

  // Folded: the inputs of beat n, drawn once and held on every clock up to its ce.
  size_t held = sched.size();
  uint8_t held_side = 0, held_left = 0, held_right = 0;
  sm::CensusVec held_cl{}, held_cr{};
  int warm = fold - 1;
  for (size_t n = 0; n < sched.size();) {
    // Folded: the reset starts the sub-steps of the first beat like a ce; its ce comes
    // F clocks later at the earliest.
    bool ce = false;
    if (warm > 0) {
      --warm;
      t->ce = 0;
    } else {
      ce = t.next_ce();
    }
    if (fold > 1) {
      if (held != n) {
        const auto& b = sched[n];
        held = n;
        held_side = b.side;
        if (b.frame >= 0) {
          held_cl = cl[b.frame].at(b.x, b.y);
          held_cr = cr[b.frame].at(b.x, b.y);
          held_left = left[b.frame].at(b.x, b.y);
          held_right = right[b.frame].at(b.x, b.y);
        } else {
          held_cl = garbage(rng);
          held_cr = garbage(rng);
          held_left = static_cast<uint8_t>(rng());
          held_right = static_cast<uint8_t>(rng());
        }
      }
      t->s_side = held_side;
      sm::test::set_port_u64(t->s_cl, held_cl, cb);
      sm::test::set_port_u64(t->s_cr, held_cr, cb);
      t->s_left = held_left;
      t->s_right = held_right;
    } else if (ce && sched[n].frame >= 0) {
      const auto& b = sched[n];
      t->s_side = b.side;
      sm::test::set_port_u64(t->s_cl, cl[b.frame].at(b.x, b.y), cb);
      sm::test::set_port_u64(t->s_cr, cr[b.frame].at(b.x, b.y), cb);
      t->s_left = left[b.frame].at(b.x, b.y);
      t->s_right = right[b.frame].at(b.x, b.y);
    } else {
      t->s_side = ce ? sched[n].side : static_cast<uint8_t>(rng() & 31);
      sm::test::set_port_u64(t->s_cl, garbage(rng), cb);
      sm::test::set_port_u64(t->s_cr, garbage(rng), cb);
      t->s_left = static_cast<uint8_t>(rng());
      t->s_right = static_cast<uint8_t>(rng());
    }
    t.tick();
    if (!ce) continue;
    ++n;
    if (!(t->m_side & sm::test::kReal)) continue;
    const auto p = t.next_out(t->m_side);
    if (!p) break;
    // one check per pixel: the pixel passes through, then every level's cost
    std::string what;
    if (t->m_left != left[p->frame].at(p->x, p->y))
      what = fmt::format("left expected {} got {}", left[p->frame].at(p->x, p->y), t->m_left);
    for (int d = 0; d < kDisp && what.empty(); ++d) {
      const unsigned got = sm::test::plane_bits(t->m_cost, d, cw, kDisp);
      const unsigned exp = cost[p->frame].at(p->x, p->y, d) >> hw.cost_shift;
      if (got != exp) what = fmt::format("d {}: expected {} got {}", d, exp, got);
    }
    t.check(what.empty(), [&] { return fmt::format("frame {} x {} y {} {}", p->frame, p->x, p->y, what); });
  }
  t.all_out();
  return t.finish(fmt::format("tb_cost MAX_WIDTH={} CENSUS={} DISP={} PU={} COST_SHIFT={} AD_SHIFT={} AD_MAX={} W={}",
                              kMaxWidth, kCensus, kDisp, pu, hw.cost_shift, hw.ad_shift, hw.ad_max, w));
}
