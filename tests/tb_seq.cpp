// Block test of sm_seq: camera streams (random idle cycles, with and without blanking,
// continuous, faulty) go in; every beat taken on ce comes out. The real beats must equal
// the framing model sm::seq_frames() (model/seq.hpp: the sequencer's fault rules applied
// to the pixel sequence, docs/streams.md) pixel for pixel; rows must be exactly W beats with correct
// sof/sol/ftag; virtual rows only after complete frames, at most FLUSH_ROWS per gap,
// exactly FLUSH_ROWS before a width change and after the last frame; fault pulses must
// match the model's counts; a continuous stream with ce = beat_valid never sees tready low.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include SM_VTOP_H
#include "seq.hpp"
#include "sm_block_test.hpp"

using Bench = sm::test::BlockTest<SM_VTOP>;

namespace {

// A piece of camera stream sent with one host setting.
struct Segment {
  int w = 37, h = 6;
  bool enable = true;
  bool drain_before = false;  // let the sequencer run empty before changing settings
  std::vector<sm::CamPixel> px;
  int hblank = 0;  // idle cycles after each tlast
  int vblank = 0;  // idle cycles after the segment
};

std::mt19937 g_rng(4242);

// Lines of the given lengths (negative: no tlast at the end), tuser on the first pixel.
std::vector<sm::CamPixel> lines(const std::vector<int>& lengths, bool sof = true) {
  std::vector<sm::CamPixel> v;
  for (size_t l = 0; l < lengths.size(); ++l) {
    const int len = std::abs(lengths[l]);
    for (int x = 0; x < len; ++x) {
      sm::CamPixel p;
      p.data = static_cast<uint16_t>(g_rng());
      p.user = sof && l == 0 && x == 0;
      p.last = x == len - 1 && lengths[l] > 0;
      v.push_back(p);
    }
  }
  return v;
}
std::vector<sm::CamPixel> good(int w, int h) { return lines(std::vector<int>(static_cast<size_t>(h), w)); }

struct Beat {
  uint8_t side;
  uint8_t left, right;
};

struct RunOut {
  std::vector<Beat> beats;
  std::vector<std::pair<int, int>> starts;  // host (w, h) at each frame_start
  sm::SeqFaultCounts err{};
  uint64_t stall_cycles = 0;  // tvalid && !tready
};

constexpr int kFlush = SM_P_FLUSH_ROWS;
constexpr int kMaxW = SM_P_MAX_WIDTH;

// Each run starts from a new model (its own coverage file).
RunOut run(Bench& t, const std::vector<Segment>& segs, int idle_percent, int ce_idle_percent, uint32_t seed) {
  RunOut out;
  t.new_model();
  auto* top = &t.tb().top();
  std::mt19937 rng(seed);
  // not next_ce(): ce also waits for beat_valid
  sm::test::CeGen room(seed * 7 + 1, ce_idle_percent);
  auto tick = [&] { t.tick(); };
  top->s_axis_tvalid = 0;
  top->ce = 0;
  top->enable = 1;
  top->host_width = segs.empty() ? kMaxW : segs[0].w;
  top->host_height = segs.empty() ? 16 : segs[0].h;
  t.reset(4);
  // One clock: drive inputs, decide ce, record, tick.
  auto cycle = [&](bool valid, const sm::CamPixel* p) -> bool {
    top->s_axis_tvalid = valid;
    if (valid) {
      top->s_axis_tdata = p->data;
      top->s_axis_tuser = p->user;
      top->s_axis_tlast = p->last;
    } else {  // garbage while idle
      top->s_axis_tdata = static_cast<uint16_t>(rng());
      top->s_axis_tuser = rng() & 1;
      top->s_axis_tlast = rng() & 1;
    }
    const bool r = room.next();
    top->ce = top->beat_valid && r;
    top->eval();
    const bool hs = valid && top->s_axis_tready;
    if (valid && !top->s_axis_tready) ++out.stall_cycles;
    if (top->ce) out.beats.push_back({top->beat_side, top->beat_left, top->beat_right});
    if (top->frame_start) out.starts.emplace_back(top->host_width, top->host_height);
    for (int e = 0; e < sm::kNumSeqFaults; ++e)
      if (top->err_pulse >> e & 1) ++out.err[static_cast<size_t>(e)];
    tick();
    return hs;
  };
  const int drain = 4 * (kMaxW + 64) * (kFlush + 4) * 100 / (100 - ce_idle_percent);
  for (auto& s : segs) {
    if (s.drain_before)
      for (int i = 0; i < drain; ++i) cycle(false, nullptr);
    top->host_width = s.w;
    top->host_height = s.h;
    top->enable = s.enable;
    for (const auto& p : s.px) {
      while (static_cast<int>(rng() % 100) < idle_percent) cycle(false, nullptr);
      while (!cycle(true, &p)) {
      }
      if (p.last)
        for (int i = 0; i < s.hblank; ++i) cycle(false, nullptr);
    }
    for (int i = 0; i < s.vblank; ++i) cycle(false, nullptr);
  }
  for (int i = 0; i < drain; ++i) cycle(false, nullptr);
  return out;
}

// Checks the beats of one run against the model.
void verify(Bench& t, const std::string& name, const std::vector<Segment>& segs, const RunOut& o) {
  std::vector<sm::SeqInput> all;
  for (const auto& s : segs)
    for (const auto& p : s.px) all.push_back({p, {static_cast<uint16_t>(s.w), static_cast<uint16_t>(s.h), s.enable}});
  const sm::SeqResult m = sm::seq_frames(all);
  const auto& F = m.frames;
  fmt::print("{}: {} frames, {} beats, fault pulses {} {} {} {} {} {} (short long missing extra few many)\n", name,
             F.size(), o.beats.size(), o.err[0], o.err[1], o.err[2], o.err[3], o.err[4], o.err[5]);
  t.check(o.starts.size() == F.size(),
          fmt::format("{}: {} frame_start pulses, model has {} frames", name, o.starts.size(), F.size()));
  for (size_t f = 0; f < std::min(F.size(), o.starts.size()); ++f)
    t.check(o.starts[f] == std::make_pair(F[f].w, F[f].h),
            fmt::format("{}: frame {} latched {}x{}, model {}x{}", name, f, o.starts[f].first, o.starts[f].second,
                        F[f].w, F[f].h));
  for (size_t e = 0; e < sm::kNumSeqFaults; ++e)
    t.check(o.err[e] == m.faults[e],
            fmt::format("{}: error class {}: {} pulses, model {}", name, e, o.err[e], m.faults[e]));

  // Walk the beats row by row.
  size_t b = 0;
  int frame = -1, row = 0, vrows_since = 0, ftag = -1;
  int last_w = -1;
  while (b < o.beats.size()) {
    const Beat& s0 = o.beats[b];
    if (!t.check(s0.side & sm::test::kSol, fmt::format("{}: beat {} should start a row", name, b))) return;
    const bool real = s0.side & sm::test::kReal;
    const bool sof = s0.side & sm::test::kSof;
    const int tag = s0.side >> 3;
    if (real && sof) {  // a new frame
      if (frame >= 0)
        t.check(row == F[static_cast<size_t>(frame)].h, fmt::format("{}: frame {} had {} rows", name, frame, row));
      ++frame;
      if (!t.check(frame < static_cast<int>(F.size()), fmt::format("{}: more frames than the model", name))) return;
      if (last_w >= 0 && F[static_cast<size_t>(frame)].w != last_w)
        t.check(vrows_since == kFlush,
                fmt::format("{}: width change before frame {} after {} virtual rows", name, frame, vrows_since));
      t.check(tag == (frame & 3), fmt::format("{}: frame {} ftag {}", name, frame, tag));
      ftag = tag;
      row = 0;
      vrows_since = 0;
      last_w = F[static_cast<size_t>(frame)].w;
    } else if (real) {
      if (!t.check(frame >= 0 && row < F[static_cast<size_t>(frame)].h,
                   fmt::format("{}: real row without sof (frame {}, row {})", name, frame, row)))
        return;
    } else {
      t.check(frame >= 0 && row == F[static_cast<size_t>(frame)].h,
              fmt::format("{}: virtual row inside or before a frame (frame {}, row {})", name, frame, row));
      t.check(tag == ftag, fmt::format("{}: virtual row ftag {} after frame ftag {}", name, tag, ftag));
      ++vrows_since;
      t.check(vrows_since <= kFlush, fmt::format("{}: {} virtual rows after frame {}", name, vrows_since, frame));
    }
    const int w = last_w;
    if (!t.check(b + static_cast<size_t>(w) <= o.beats.size(), fmt::format("{}: truncated row", name))) return;
    for (int x = 0; x < w; ++x) {
      const Beat& bt = o.beats[b + static_cast<size_t>(x)];
      const uint8_t want_side =
          static_cast<uint8_t>((tag << 3) | (real ? 1 : 0) | (x == 0 ? 4 : 0) | (real && x == 0 && row == 0 ? 2 : 0));
      if (!t.check(bt.side == want_side, fmt::format("{}: frame {} row {} x {}: side {:x} expected {:x}", name, frame,
                                                     row, x, bt.side, want_side)))
        return;
      if (real) {
        const sm::SeqFrame& mf = F[static_cast<size_t>(frame)];
        if (!t.check(row * w + x < mf.beats,
                     fmt::format("{}: frame {} x {} y {}: beyond the model's {} beats", name, frame, x, row, mf.beats)))
          return;
        const uint16_t want = mf.data(x, row);
        const uint16_t got = static_cast<uint16_t>(bt.left | (bt.right << 8));
        t.check(got == want,
                fmt::format("{}: frame {} x {} y {}: expected 0x{:04x} got 0x{:04x}", name, frame, x, row, want, got));
      }
    }
    b += static_cast<size_t>(w);
    if (real) ++row;
  }
  t.check(frame + 1 == static_cast<int>(F.size()),
          fmt::format("{}: {} frames out, model {}", name, frame + 1, F.size()));
  if (!F.empty()) {
    t.check(row == F.back().h, fmt::format("{}: last frame incomplete", name));
    t.check(vrows_since == kFlush, fmt::format("{}: {} virtual rows after the last frame", name, vrows_since));
  }
}

}  // namespace

int main(int argc, char** argv) {
  Bench t{"sm_seq block test"};
  bool paper = false;
  t.flag("--paper", paper, "the paper point's widths and heights (320 and 160 wide)");
  if (auto rc = t.parse(argc, argv)) return *rc;
  const int W = paper ? 320 : 37, H = paper ? 3 : 6;
  const int W2 = paper ? 160 : 21;

  {  // 1. good frames, random idle input, blanking, random ce gaps
    std::vector<Segment> s;
    for (int f = 0; f < 3; ++f) {
      Segment g;
      g.w = W;
      g.h = H;
      g.px = good(W, H);
      g.hblank = 5;
      g.vblank = f == 1 ? 0 : W * 2;
      s.push_back(g);
    }
    const RunOut o = run(t, s, 20, 30, 1);
    verify(t, "blanking", s, o);
  }
  {  // 2. continuous stream, ce = beat_valid: tready never low
    std::vector<Segment> s(1);
    s[0].w = W;
    s[0].h = H;
    for (int f = 0; f < 4; ++f) {
      auto p = good(W, H);
      s[0].px.insert(s[0].px.end(), p.begin(), p.end());
    }
    const RunOut o = run(t, s, 0, 0, 2);
    verify(t, "continuous", s, o);
    t.check(o.stall_cycles == 0, fmt::format("continuous: tready low for {} cycles", o.stall_cycles));
  }
  {  // 3. faults
    std::vector<Segment> s;
    auto seg = [&](std::vector<sm::CamPixel> px) {
      Segment g;
      g.w = W;
      g.h = H;
      g.px = std::move(px);
      g.vblank = static_cast<int>(g_rng() % 3) * W;
      s.push_back(g);
    };
    seg(lines({W, W}, false));                                    // missing sof after reset
    seg(good(W, H));                                              // good
    seg(lines({W, W - 5, W, W + 7, W, W}));                       // short line, long line
    seg(lines({W, W, -(W / 2)}));                                 // sof mid-line follows
    seg(lines({W, W, W}));                                        // sof at a line start too early
    seg(lines(std::vector<int>(static_cast<size_t>(H + 2), W)));  // too many lines
    seg(good(W, H));
    seg(lines(std::vector<int>(static_cast<size_t>(H - 1), W)));
    s.back().px.back().last = false;            // long last line, then the next frame
    seg(lines({-(W + 3), W, W, W, W, W + 1}));  // long first line without tlast
    seg(lines({1, W, W, W, W, W}));             // one-pixel line
    seg(good(W, H));
    const RunOut o = run(t, s, 15, 25, 3);
    verify(t, "faults", s, o);
  }
  {  // 4. width changes and enable
    std::vector<Segment> s;
    auto seg = [&](int w, int h, bool en, bool drain, int vblank) {
      Segment g;
      g.w = w;
      g.h = h;
      g.enable = en;
      g.drain_before = drain;
      g.px = good(w, h);
      g.vblank = vblank;
      s.push_back(g);
    };
    seg(W, H, true, false, 0);
    seg(W2, H + 1, true, true, 0);  // width change with the camera idle (flushed already)
    // height change without a pause; the frame is longer than the input FIFO, so its
    // sof has been taken before the host values change for the next segment
    seg(W2, H + 4, true, false, 0);
    seg(W, H, true, false, 0);  // width change, no blanking: flush rows are inserted
    seg(W, H, false, true, 0);  // disabled: dropped silently
    seg(W, H, true, true, W);
    const RunOut o = run(t, s, 10, 20, 4);
    verify(t, "width/enable", s, o);
  }

  return t.finish(fmt::format("tb_seq MAX_WIDTH={} FLUSH_ROWS={}", kMaxW, kFlush));
}
