// Block test of sm_brightness against the model's brightness() (docs/algorithm.md,
// section 1). Back-to-back frames of odd width with random ce gaps; each frame gets its
// own random gains/offsets (including ones that saturate at 0 and at 255) presented on
// the sof beat only -- garbage on every other beat checks that they are latched there.
#include <fmt/format.h>

#include <random>
#include <vector>

#include SM_VTOP_H
#include "pre.hpp"
#include "sm_block_test.hpp"

using sm::test::BeatInfo;

namespace {
struct Params {
  uint16_t gain_l, gain_r;
  int16_t off_l, off_r;
};
}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_brightness block test"};
  int w = 37;
  std::vector<int> heights = {9, 5, 12, 7, 6, 8};
  t.option("--width", w, "active width");
  t.option("--heights", heights, "rows of each frame, sent back to back");
  if (auto rc = t.parse(argc, argv)) return *rc;
  std::mt19937 rng(2024), garbage(77);
  std::uniform_int_distribution<int> pix(0, 255), gain(0, 1023), off(-256, 255);
  // Frame 0 identity, 1 saturates high (gain 4x, +255), 2 saturates low (-256), the rest
  // random.
  std::vector<Params> prm = {{256, 256, 0, 0}, {1023, 700, 255, 100}, {100, 256, -256, -100}};
  while (prm.size() < heights.size())
    prm.push_back({static_cast<uint16_t>(gain(rng)), static_cast<uint16_t>(gain(rng)), static_cast<int16_t>(off(rng)),
                   static_cast<int16_t>(off(rng))});

  std::vector<sm::Image8> in_l, in_r, want_l, want_r;
  for (size_t f = 0; f < heights.size(); ++f) {
    sm::Image8 l(w, heights[f]), r(w, heights[f]);
    for (auto& p : l.px) p = static_cast<uint8_t>(pix(rng));
    for (auto& p : r.px) p = static_cast<uint8_t>(pix(rng));
    in_l.push_back(l);
    in_r.push_back(r);
    want_l.push_back(sm::brightness(l, prm[f].gain_l, prm[f].off_l));
    want_r.push_back(sm::brightness(r, prm[f].gain_r, prm[f].off_r));
  }

  auto& top = t.tb().top();
  top.ce = 1;
  t.reset(3);

  const auto sched = sm::test::make_schedule(w, heights, 2, 1);
  t.expect_frames(w, heights);
  t.ce_schedule(5, 35);
  size_t bi = 0;
  auto garbage_params = [&] {
    top.gain_l = garbage() & 1023;
    top.gain_r = garbage() & 1023;
    top.offset_l = garbage() & 511;
    top.offset_r = garbage() & 511;
  };
  while (bi < sched.size()) {
    const bool ce = t.next_ce();
    garbage_params();
    if (ce) {
      const BeatInfo& b = sched[bi++];
      top.s_side = b.side;
      top.s_left = b.frame >= 0 ? in_l[b.frame].at(b.x, b.y) : garbage() & 255;
      top.s_right = b.frame >= 0 ? in_r[b.frame].at(b.x, b.y) : garbage() & 255;
      if (b.side & sm::test::kSof) {
        const Params& p = prm[b.frame];
        top.gain_l = p.gain_l;
        top.gain_r = p.gain_r;
        top.offset_l = p.off_l & 511;
        top.offset_r = p.off_r & 511;
      }
    } else {
      top.s_side = garbage() & 31;
      top.s_left = garbage() & 255;
      top.s_right = garbage() & 255;
    }
    t.tick();
    if (!ce || !(top.m_side & sm::test::kReal)) continue;
    const auto o = t.next_out(top.m_side);
    if (!o) break;
    const int el = want_l[o->frame].at(o->x, o->y), er = want_r[o->frame].at(o->x, o->y);
    t.check(el == top.m_left && er == top.m_right, [&] {
      return fmt::format("frame {} x {} y {} expected {}/{} got {}/{}", o->frame, o->x, o->y, el, er, top.m_left,
                         top.m_right);
    });
  }
  t.all_out();
  return t.finish("tb_brightness");
}
