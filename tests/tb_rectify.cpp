// Block test of sm_rectify against the model's rectify() (docs/algorithm.md, section 2).
// Two sessions of back-to-back frames with random clock-enable gaps. Before each session
// both grid banks are written through grid_we (with garbage in the unused points first)
// while virtual rows stream through; each frame selects a bank and enable, presented only
// on the beat where the stage starts the frame's output row 0 (garbage elsewhere, so the
// latching is checked). Grids: identity, smooth warps with sub-pixel shifts, and random
// grids with vertical offsets beyond RECT_RADIUS, positions outside the image and
// saturated values; one frame runs with enable = 0.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include SM_VTOP_H
#include "calib_file.hpp"
#include "pre.hpp"
#include "sm_block_test.hpp"

using sm::test::BeatInfo;

namespace {

constexpr int kMaxW = SM_P_MAX_WIDTH;
constexpr int kMaxH = SM_P_MAX_HEIGHT;
constexpr int kR = SM_P_RECT_RADIUS;

int16_t q5(double v) { return static_cast<int16_t>(std::clamp(std::lround(v * 32), -32768L, 32767L)); }

sm::RectGrid smooth_grid(int w, int h, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  sm::RectGrid g = sm::RectGrid::identity(w, h);
  const double ax = 3.0 * u(rng), ay = (kR - 1.5) * std::fabs(u(rng)) + 0.5;
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx) {
      const size_t i = static_cast<size_t>(gy) * g.gw + gx;
      g.sx[i] = q5(16.0 * gx + ax * std::sin(0.7 * gy + 0.3 * gx) + u(rng));
      g.sy[i] = q5(16.0 * gy + ay * std::cos(0.5 * gx + 0.4 * gy) + 0.5 * u(rng));
    }
  return g;
}

sm::RectGrid wild_grid(int w, int h, std::mt19937& rng) {
  std::uniform_int_distribution<int> dy(-2 * kR - 3, 2 * kR + 3), dx(-24, 24), fr(0, 31), pick(0, 15);
  sm::RectGrid g = sm::RectGrid::identity(w, h);
  for (int gy = 0; gy < g.gh; ++gy)
    for (int gx = 0; gx < g.gw; ++gx) {
      const size_t i = static_cast<size_t>(gy) * g.gw + gx;
      g.sx[i] = static_cast<int16_t>((16 * gx + dx(rng)) * 32 + fr(rng));
      g.sy[i] = static_cast<int16_t>((16 * gy + dy(rng)) * 32 + fr(rng));
      const int p = pick(rng);
      if (p == 0) g.sx[i] = -32768;
      if (p == 1) g.sy[i] = 32767;
      if (p == 2) g.sx[i] = static_cast<int16_t>((w + 1) * 32);  // just right of the image
    }
  return g;
}

struct Frame {
  int bank;
  bool enable;
};

struct Session {
  int width;
  std::vector<int> heights;
  std::vector<Frame> frames;
  sm::RectGrid grid[2];
};

}  // namespace

int main(int argc, char** argv) {
  sm::test::BlockTest<SM_VTOP> t{"sm_rectify block test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  const sm::HwConfig hw = sm::verilated_config();

  std::mt19937 rng(12345);
  std::vector<Session> sessions;
  {
    Session s;
    s.width = kMaxW == 64 ? 37 : kMaxW;
    s.heights = {kMaxH, kMaxH - 7, kMaxH};
    if (kMaxW > 64) s.heights.pop_back();  // paper point: keep the run short
    s.frames = {{0, true}, {1, true}, {1, false}};
    s.grid[0] = sm::RectGrid::identity(s.width, kMaxH);
    s.grid[1] = smooth_grid(s.width, kMaxH, rng);
    sessions.push_back(s);
  }
  {
    Session s;
    s.width = kMaxW == 64 ? kMaxW : kMaxW - 19;
    s.heights = {20, 31, 20};
    s.frames = {{0, true}, {1, true}, {0, true}};
    s.grid[0] = wild_grid(s.width, 20, rng);
    s.grid[1] = smooth_grid(s.width, 20, rng);
    sessions.push_back(s);
  }

  t.ce_schedule(7, 30);
  std::mt19937 garbage(99);
  auto& tb = t.tb();
  auto& top = tb.top();
  top.ce = 1;
  top.grid_we = 0;
  top.width = 37;
  t.reset(4);

  const int gwmax = sm::grid_gwmax(kMaxW), ghmax = sm::grid_ghmax(kMaxH);

  for (size_t si = 0; si < sessions.size(); ++si) {
    const Session& s = sessions[si];
    const int w = s.width;
    // Expected outputs and input images.
    std::vector<sm::Image8> in, want;
    std::uniform_int_distribution<int> pix(0, 255);
    for (size_t f = 0; f < s.heights.size(); ++f) {
      sm::Image8 img(w, s.heights[f]);
      for (auto& p : img.px) p = static_cast<uint8_t>(pix(rng));
      in.push_back(img);
      const Frame& fr = s.frames[f];
      want.push_back(sm::rectify(img, s.grid[fr.bank], fr.enable, hw));
    }

    // Grid writes (garbage everywhere first), issued one per clock while virtual rows
    // stream through with random ce.
    std::vector<std::pair<uint32_t, uint32_t>> writes;
    for (int b = 0; b < 2; ++b) {
      for (int gy = 0; gy < ghmax; ++gy)
        for (int gx = 0; gx < gwmax; ++gx)
          writes.push_back({sm::grid_waddr(hw, b, gx, gy), static_cast<uint32_t>(garbage())});
      const sm::RectGrid& g = s.grid[b];
      for (int gy = 0; gy < g.gh; ++gy)
        for (int gx = 0; gx < g.gw; ++gx) writes.push_back({sm::grid_waddr(hw, b, gx, gy), sm::grid_wdata(g, gx, gy)});
    }
    size_t wi = 0;
    int vx = 0;  // column of the virtual row being streamed during the writes
    bool stray = false;
    while (wi < writes.size() || vx != 0) {
      const bool ce = t.next_ce();
      top.grid_we = wi < writes.size();
      if (top.grid_we) {
        top.grid_waddr = writes[wi].first;
        top.grid_wdata = writes[wi].second;
        ++wi;
      }
      top.s_side = ce ? static_cast<uint8_t>(vx == 0 ? sm::test::kSol : 0) : garbage() & 31;
      top.s_pix = garbage() & 255;
      top.enable = garbage() & 1;
      top.grid_bank = garbage() & 1;
      tb.tick();
      if (ce && ++vx == top.width) vx = 0;
      if (ce && (top.m_side & sm::test::kReal)) {
        t.fail(fmt::format("real output beat during the grid writes of session {}", si));
        stray = true;
        break;
      }
    }
    if (stray) break;
    top.grid_we = 0;
    top.width = w;

    // Stream the frames.
    const auto sched = sm::test::make_schedule(w, s.heights, kR + 2);
    std::map<size_t, Frame> latch_at;  // schedule index of each frame's output row 0 start
    {
      size_t i = 0;
      for (size_t f = 0; f < s.heights.size(); ++f) {
        latch_at[i + static_cast<size_t>(kR + 1) * w] = s.frames[f];
        i += static_cast<size_t>(s.heights[f]) * w;
      }
    }
    t.expect_frames(w, s.heights);
    const std::string where = fmt::format("session {}: ", si);
    size_t bi = 0;
    while (bi < sched.size()) {
      const bool ce = t.next_ce();
      if (ce) {
        const BeatInfo& b = sched[bi];
        top.s_side = b.side;
        top.s_pix = b.frame >= 0 ? in[b.frame].at(b.x, b.y) : garbage() & 255;
        auto it = latch_at.find(bi);
        top.enable = it != latch_at.end() ? it->second.enable : garbage() & 1;
        top.grid_bank = it != latch_at.end() ? it->second.bank : garbage() & 1;
        ++bi;
      } else {
        top.s_side = garbage() & 31;
        top.s_pix = garbage() & 255;
        top.enable = garbage() & 1;
        top.grid_bank = garbage() & 1;
      }
      tb.tick();
      if (!ce || !(top.m_side & sm::test::kReal)) continue;
      const auto o = t.next_out(top.m_side, where);
      if (!o) break;
      const int exp = want[o->frame].at(o->x, o->y);
      t.check(exp == top.m_pix, [&] {
        return fmt::format("{}frame {} x {} y {} expected {} got {}", where, o->frame, o->x, o->y, exp, top.m_pix);
      });
    }
    // a stream out of order or short stops the run: the next session would start mid-frame
    if (!t.all_out(where)) break;
  }
  return t.finish(fmt::format("tb_rectify MAX_WIDTH={} MAX_HEIGHT={} RECT_RADIUS={}", kMaxW, kMaxH, kR));
}
