// Block test of sm_census against the model's census_transform: random images, frames
// of different heights back to back, an odd width, virtual flush rows and ce gaps with
// garbage on every beat the block must ignore. Every real output pixel is compared.
#include <fmt/format.h>

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

std::string hex(const sm::CensusVec& v) { return fmt::format("{:016x}{:016x}{:016x}{:016x}", v[3], v[2], v[1], v[0]); }

sm::Image8 random_image(int w, int h, std::mt19937& rng) {
  sm::Image8 im(w, h);
  // a few grey levels so equal neighbours (bit 0) are frequent too
  for (auto& p : im.px) p = static_cast<uint8_t>((rng() % 3 == 0) ? (rng() & 3) * 64 : rng());
  return im;
}

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_census block test"};
  int w = 37;
  std::vector<int> heights = {13, 2, 7};  // H = 2 is shorter than the window
  t.option("--width", w, "active width").range(1, kMaxWidth);
  t.option("--heights", heights, "rows of each frame, sent back to back");
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int r = (kCensus - 1) / 2;
  const sm::HwConfig hw = sm::verilated_config();
  const int cb = hw.census_bits();

  std::mt19937 rng(1234);
  std::vector<sm::Image8> left, right;
  std::vector<sm::CensusImage> cl, cr;
  for (int h : heights) {
    left.push_back(random_image(w, h, rng));
    right.push_back(random_image(w, h, rng));
    cl.push_back(sm::census_transform(left.back(), hw));
    cr.push_back(sm::census_transform(right.back(), hw));
  }
  const auto sched = sm::test::make_schedule(w, heights, r + 2);

  t.ce_schedule(0xce11u, 30);
  t.expect_frames(w, heights);
  t->width = w;
  t->ce = 1;
  t->s_side = 0;
  t.reset(3);

  uint8_t last_side = 0;
  for (size_t n = 0; n < sched.size();) {
    const bool ce = t.next_ce();
    if (ce && sched[n].frame >= 0) {
      const auto& b = sched[n];
      t->s_side = b.side;
      t->s_left = left[b.frame].at(b.x, b.y);
      t->s_right = right[b.frame].at(b.x, b.y);
    } else {
      // virtual beat (its sideband is real) or an idle cycle (all garbage)
      t->s_side = ce ? sched[n].side : static_cast<uint8_t>(rng() & 31);
      t->s_left = static_cast<uint8_t>(rng());
      t->s_right = static_cast<uint8_t>(rng());
    }
    t.tick();
    if (!ce) {
      if (t->m_side != last_side) t.fail("m_side changed without ce");
      continue;
    }
    ++n;
    last_side = t->m_side;
    if (!(t->m_side & sm::test::kReal)) continue;
    const auto p = t.next_out(t->m_side);
    if (!p) break;
    const auto gl = sm::test::get_port_u64<4>(t->m_cl, cb);
    const auto gr = sm::test::get_port_u64<4>(t->m_cr, cb);
    const auto& el = cl[p->frame].at(p->x, p->y);
    const auto& er = cr[p->frame].at(p->x, p->y);
    const int eleft = left[p->frame].at(p->x, p->y), eright = right[p->frame].at(p->x, p->y);
    t.check(gl == el && gr == er && t->m_left == eleft && t->m_right == eright, [&] {
      return fmt::format(
          "frame {} x {} y {}:\n  cl expected {} got {}\n  cr expected {} got {}\n  left expected {} got {}\n"
          "  right expected {} got {}",
          p->frame, p->x, p->y, hex(el), hex(gl), hex(er), hex(gr), eleft, t->m_left, eright, t->m_right);
    });
  }
  t.all_out();
  return t.finish(fmt::format("tb_census MAX_WIDTH={} CENSUS={} W={}", kMaxWidth, kCensus, w));
}
