// Cycle-accurate simulation engine for sm_top: streams camera frames into
// s_axis_video with a camera's timing (or continuously), takes the disparity stream and
// the object packets from the IP, and measures cycles. Shared by stereo_sim and the
// system tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "sm_axil.hpp"
#include "sm_handshakes.hpp"
#include "sm_host.hpp"
#include "sm_regmap.hpp"
#include "sm_tb.hpp"
#include "outword.hpp"
#include "sm_types.hpp"

namespace sm {

struct CameraTiming {
  bool continuous = false;    // no blanking at all
  int hblank = 80;            // idle cycles after each line
  int vblank_lines = 22;      // idle lines (of width + hblank cycles) after each frame
  double pixel_clock_hz = 0;  // 0: derived as (W+hblank)*(H+vblank)*fps
  double fps = 30.0;
  // aclk, the core clock, in Hz. 0: aclk is the camera's pixel clock (a camera pixel
  // every aclk during a line, the blanking in aclk cycles). Otherwise the camera's
  // pixels arrive on aclk at the camera's own cadence: camera clock k (counted over
  // lines and blanking from the first pixel) is due at aclk cycle ceil(k * core_hz /
  // clock_hz), and a stalled pixel does not delay the ones after it (a camera does not
  // wait).
  double core_hz = 0;
  int idle_percent = 0;          // random extra idle cycles on the input (tests)
  int backpressure_percent = 0;  // random tready=0 on the outputs (tests)
  // m_axis_obj_tready held low until output frame n has sent its first row (tests: with
  // n = 2, frame 0's packet is still waiting when frame 1's list is published, so that
  // list's packet is lost and frame 2's packet carries the lost bit)
  int obj_hold_frames = 0;
  int clocks_per_pixel = 1;  // the IP's DISP / PU (bounds the run's cycle limit)
  uint32_t seed = 1;
  double clock_hz(int w, int h) const {
    if (pixel_clock_hz > 0) return pixel_clock_hz;
    return continuous ? double(w) * h * fps : double(w + hblank) * (h + vblank_lines) * fps;
  }
  // The IP's side of the timing: fold = DISP / PU clocks per pixel and the core clock
  // core_mhz (0: at fold 1 aclk is the camera's pixel clock, at fold > 1 it is fold times
  // the pixel clock, the slowest aclk the input FIFO rule of docs/streams.md allows).
  void set_core(int fold, double core_mhz, int w, int h) {
    clocks_per_pixel = fold;
    core_hz = core_mhz > 0 ? core_mhz * 1e6 : fold > 1 ? fold * clock_hz(w, h) : 0.0;
  }
  // aclk cycles per camera clock (1 when aclk is the camera's pixel clock)
  double aclk_per_camera_clock(int w, int h) const { return core_hz > 0 ? core_hz / clock_hz(w, h) : 1.0; }
  double aclk_hz(int w, int h) const { return core_hz > 0 ? core_hz : clock_hz(w, h); }
};

// One object as it leaves the object stream (docs/algorithm.md section 8).
struct ObjWords {
  std::vector<uint32_t> words;  // one packet
};

struct FrameStats {
  uint64_t sof_in_cycle = 0;     // cycle the frame's first pixel entered
  uint64_t last_in_cycle = 0;    // cycle its last pixel entered
  uint64_t first_out_cycle = 0;  // cycle its first disparity left
  uint64_t last_out_cycle = 0;   // cycle its last disparity left
};

struct SimResult {
  std::vector<OutImage> frames;  // output words of each frame out of m_axis
  std::vector<ObjWords> object_packets;
  std::vector<FrameStats> stats;
  uint64_t cycles = 0;
  uint64_t input_stall_cycles = 0;       // camera pixel waiting with tready low
  std::string framing_error;             // empty when every frame was well-formed
  uint64_t host_writes = 0;              // AXI4-Lite writes of the register schedule
  std::vector<std::string> host_errors;  // refused writes, changes that came too late
};

// Frames streamed from their source: the camera asks for frame f (f = 0, 1, ... in
// order) when its first pixel is due, and each disparity frame goes to `out` as it
// leaves the IP (then SimResult::frames stays empty), so a run holds a few frames, not
// all of them (sm_frame_source.hpp).
using StereoFrame = std::pair<Image8, Image8>;
struct FrameFeed {
  size_t count = 0;                                     // frames of the run
  std::function<const StereoFrame&(size_t f)> frame;    // the camera's frame f
  std::function<void(size_t f, OutImage&& words)> out;  // empty: kept in SimResult::frames
};

struct VcdWindow {
  std::string path;     // empty: no dump
  int frame = 0;        // start at this input frame ...
  int line = 0;         // ... and this input line
  uint64_t cycles = 0;  // dump this many cycles (0: use lines)
  int lines = 4;        // or this many input line periods
  TraceScope scope;     // the signals dumped (default: every traced signal)
};

template <class Top>
class SimEngine {
 public:
  explicit SimEngine(Testbench<Top>& tb) : tb_(tb), axil_(tb.top(), [this] { step(); }), agent_(tb.top()) {}

  AxilMaster<Top>& axil() { return axil_; }

  void reset(int cycles = 8) {
    auto& t = tb_.top();
    t.aresetn = 0;
    t.s_axis_tvalid = 0;
    t.m_axis_tready = 1;
    t.m_axis_obj_tready = 1;
    axil_.idle();
    for (int i = 0; i < cycles; ++i) tb_.tick();
    t.aresetn = 1;
    tb_.tick();
  }

  // Progress callback: called with (frames done, frames total) after each output frame.
  std::function<void(size_t, size_t)> on_frame;
  // Progress within a frame: called with (output frame, row) after each complete output
  // row (once per row: the per-clock loop stays cheap).
  std::function<void(size_t, int)> on_row;

  // `host`: a register schedule (plan_register_schedule) the host runs over AXI4-Lite
  // while the camera streams.
  SimResult run(const std::vector<std::pair<Image8, Image8>>& frames, int width, int height, const CameraTiming& timing,
                const VcdWindow& vcd = {}, uint64_t max_cycles = 0, const std::vector<HostOp>* host = nullptr) {
    FrameFeed feed;
    feed.count = frames.size();
    feed.frame = [&frames](size_t f) -> const StereoFrame& { return frames[f]; };
    return run(feed, width, height, timing, vcd, max_cycles, host);
  }
  SimResult run(const FrameFeed& frames, int width, int height, const CameraTiming& timing, const VcdWindow& vcd = {},
                uint64_t max_cycles = 0, const std::vector<HostOp>* host = nullptr) {
    RunState s(frames, width, height, timing, vcd, host);
    start_run(s);
    if (max_cycles == 0) max_cycles = default_max_cycles(s);
    while (s.oframe < frames.count) {
      if (tb_.cycles() - s.start > max_cycles)
        throw std::runtime_error(fmt::format("simulation made no progress: {} of {} frames out after {} cycles",
                                             s.oframe, frames.count, tb_.cycles() - s.start));
      update_wave(s);
      clock_streams(s);
    }
    drain(s);
    if (s.vcd_on) tb_.close_trace();
    s.res.cycles = tb_.cycles() - s.start;
    return std::move(s.res);
  }

  // Register schedule: starts the next operation when the agent is free (kWaitOutput
  // completes here, without a bus access).
  void host_start(const std::vector<HostOp>* host, size_t& hi, size_t frames_out) {
    if (!host || agent_.busy()) return;
    while (hi < host->size() && (*host)[hi].kind == HostOp::kWaitOutput && frames_out >= (*host)[hi].n) ++hi;
    if (hi >= host->size()) return;
    const HostOp& op = (*host)[hi];
    if (op.kind == HostOp::kWrite)
      agent_.write(op.addr, op.data);
    else if (op.kind != HostOp::kWaitOutput)
      agent_.read(regmap::kSTATUS);
  }
  // ... and completes it after the clock edge that ended its bus access.
  template <class Started>
  void host_done(const std::vector<HostOp>* host, size_t& hi, const Started& started, SimResult& res) {
    if (!host || !agent_.update()) return;
    const HostOp& op = (*host)[hi];
    if (op.kind == HostOp::kWrite) {
      ++res.host_writes;
      if (agent_.resp() != 0)
        res.host_errors.push_back(
            fmt::format("frame {}: write of 0x{:08x} to 0x{:04x} refused", op.frame, op.data, op.addr));
      ++hi;
    } else if (op.kind == HostOp::kWaitStarted) {
      if (started(agent_.rdata()) >= op.n) ++hi;
    } else if (op.kind == HostOp::kCheckNotStarted) {
      if (started(agent_.rdata()) > op.n)
        res.host_errors.push_back(
            fmt::format("frame {}: its register writes ended after the frame had started (too late)", op.frame));
      ++hi;
    }
  }

  // Advances one clock with the streams idle (used by register accesses).
  void step() {
    auto& t = tb_.top();
    t.s_axis_tvalid = 0;
    t.m_axis_tready = 1;
    t.m_axis_obj_tready = 1;
    tb_.tick();
  }

 private:
  // One run(): its inputs, the camera's position, the output frame being assembled, the
  // host's next operation and the wave window.
  struct RunState {
    RunState(const FrameFeed& frames_, int width_, int height_, const CameraTiming& timing_, const VcdWindow& vcd_,
             const std::vector<HostOp>* host_)
        : frames(frames_), width(width_), height(height_), timing(timing_), vcd(vcd_), host(host_) {}
    const FrameFeed& frames;
    const StereoFrame* cam = nullptr;  // the camera's frame f (fetched at its first pixel)
    size_t cam_f = ~size_t{0};
    int width, height;
    const CameraTiming& timing;
    const VcdWindow& vcd;
    const std::vector<HostOp>* host;
    SimResult res;
    std::mt19937 rng{1};
    uint32_t count_base = 0;  // frames started before this run (STATUS.FRAME_COUNT, mod 2^16)
    size_t hi = 0;            // next host operation
    int hb = 0, vb = 0;       // blanking: cycles after a line, lines after a frame
    uint64_t line_period = 0;
    double ratio = 1;  // aclk cycles per camera clock
    uint64_t frame_ticks = 0;
    uint64_t start = 0;
    uint64_t due = 0;  // cycle the camera's next pixel is due
    size_t f = 0;      // camera: frame, column, row
    int x = 0, y = 0;
    OutImage cur;  // output: the frame being assembled, column, row, frames done
    int ox = 0, oy = 0;
    size_t oframe = 0;
    std::vector<uint32_t> pkt;  // object packet being assembled
    bool vcd_on = false;
    uint64_t vcd_end = 0;
    // frames of this run started, by a STATUS word
    uint64_t started(uint32_t status) const {
      return static_cast<uint64_t>(((status & 0xffffu) - count_base) & 0xffffu);
    }
  };

  void start_run(RunState& s) {
    const CameraTiming& timing = s.timing;
    s.count_base = s.host && !s.host->empty() ? axil_.read(regmap::kSTATUS) & 0xffffu : 0;
    s.res.stats.resize(s.frames.count);
    s.rng.seed(timing.seed);
    s.hb = timing.continuous ? 0 : timing.hblank;
    s.vb = timing.continuous ? 0 : timing.vblank_lines;
    s.line_period = static_cast<uint64_t>(s.width + s.hb);
    s.ratio = timing.aclk_per_camera_clock(s.width, s.height);
    if (timing.core_hz > 0 && s.ratio < 1.0)
      throw std::invalid_argument(fmt::format("core clock {:.3f} MHz is below the camera's pixel clock {:.3f} MHz",
                                              timing.core_hz / 1e6, timing.clock_hz(s.width, s.height) / 1e6));
    s.frame_ticks = s.line_period * static_cast<uint64_t>(s.height + s.vb);
    // The camera: pixel n of frame f is due at a fixed cycle; it never waits for the IP
    // in reality, so a pixel presented late counts as a stall.
    s.due = tb_.cycles();
    s.start = tb_.cycles();
  }

  uint64_t default_max_cycles(const RunState& s) const {
    return static_cast<uint64_t>(static_cast<double>((s.frames.count + 2) * s.line_period *
                                                     static_cast<uint64_t>(s.height + s.vb + 64) * 4) *
                                 std::max(s.ratio, static_cast<double>(s.timing.clocks_per_pixel))) +
           100000;
  }

  // VCD window: opens when the camera reaches the chosen frame/line.
  void update_wave(RunState& s) {
    const VcdWindow& vcd = s.vcd;
    if (!vcd.path.empty() && !s.vcd_on && s.vcd_end == 0 && s.f == static_cast<size_t>(vcd.frame) && s.y == vcd.line &&
        s.x == 0) {
      if (!tb_.open_trace(vcd.path, 99, vcd.scope))
#if VM_TRACE
        throw std::runtime_error(fmt::format("{}: cannot open the wave file for writing", vcd.path));
#else
        throw std::runtime_error("this simulator was built without tracing (--trace)");
#endif
      s.vcd_on = true;
      s.vcd_end = tb_.cycles() + (vcd.cycles ? vcd.cycles : vcd.lines * s.line_period);
    }
    if (s.vcd_on && tb_.cycles() >= s.vcd_end) {
      tb_.close_trace();
      s.vcd_on = false;
    }
  }

  // The camera's pixel (when due and not idle) and the outputs' tready for this clock.
  void drive_inputs(RunState& s) {
    auto& t = tb_.top();
    const CameraTiming& timing = s.timing;
    const bool have = s.f < s.frames.count && tb_.cycles() >= s.due;
    bool present = have;
    if (present && timing.idle_percent > 0 && s.x == 0 && static_cast<int>(s.rng() % 100) < timing.idle_percent)
      present = false;  // a late line start: idle cycles between pixels are in the tests' timing
    if (present && timing.idle_percent > 0 && static_cast<int>(s.rng() % 100) < timing.idle_percent) present = false;
    t.s_axis_tvalid = present;
    if (present) {
      if (s.cam_f != s.f) {
        s.cam = &s.frames.frame(s.f);
        s.cam_f = s.f;
      }
      const StereoFrame& fr = *s.cam;
      t.s_axis_tdata =
          static_cast<uint32_t>(fr.first.at(s.x, s.y)) | (static_cast<uint32_t>(fr.second.at(s.x, s.y)) << 8);
      t.s_axis_tuser = (s.x == 0 && s.y == 0);
      t.s_axis_tlast = (s.x == s.width - 1);
    }
    t.m_axis_tready =
        !(timing.backpressure_percent > 0 && static_cast<int>(s.rng() % 100) < timing.backpressure_percent);
    t.m_axis_obj_tready =
        !(timing.backpressure_percent > 0 && static_cast<int>(s.rng() % 100) < timing.backpressure_percent);
    const auto hold = static_cast<size_t>(timing.obj_hold_frames);
    if (s.oframe < hold || (s.oframe == hold && hold > 0 && s.oy == 0)) t.m_axis_obj_tready = 0;
  }

  // One clock of the streams and the host: drive, sample before the edge, tick, take.
  void clock_streams(RunState& s) {
    auto& t = tb_.top();
    drive_inputs(s);
    host_start(s.host, s.hi, s.oframe);
    t.eval();
    agent_.sample();
    const Handshakes h = Handshakes::sample(t);
    if (t.s_axis_tvalid && !t.s_axis_tready) ++s.res.input_stall_cycles;
    const uint64_t now = tb_.cycles();
    tb_.tick();
    host_done(
        s.host, s.hi, [&s](uint32_t st) { return s.started(st); }, s.res);
    if (h.in) advance_camera(s, now);
    take_obj(s, h);
    if (h.out) take_pixel(s, h, now);
  }

  // The camera's pixel was taken at cycle `now`: the next one and when it is due.
  void advance_camera(RunState& s, uint64_t now) {
    FrameStats& st = s.res.stats[s.f];
    if (s.x == 0 && s.y == 0) st.sof_in_cycle = now;
    st.last_in_cycle = now;
    if (s.timing.core_hz > 0) {
      if (++s.x == s.width) {
        s.x = 0;
        if (++s.y == s.height) {
          s.y = 0;
          ++s.f;
        }
      }
      s.due = s.start + static_cast<uint64_t>(
                            std::ceil(static_cast<double>(s.f * s.frame_ticks + s.y * s.line_period + s.x) * s.ratio));
      return;
    }
    if (++s.x == s.width) {
      s.x = 0;
      s.due = std::max(s.due + 1, now + 1 + s.hb);
      if (++s.y == s.height) {
        s.y = 0;
        ++s.f;
        s.due = now + 1 + s.hb + static_cast<uint64_t>(s.vb) * s.line_period;
      }
    } else {
      s.due = std::max(s.due + 1, now + 1);
    }
  }

  // One word of the object stream taken at this edge; a packet ends at tlast.
  void take_obj(RunState& s, const Handshakes& h) {
    if (!h.obj) return;
    s.pkt.push_back(h.obj_data);
    if (h.obj_last) {
      s.res.object_packets.push_back({s.pkt});
      s.pkt.clear();
    }
  }

  // One disparity pixel taken at cycle `now`, its framing checked.
  void take_pixel(RunState& s, const Handshakes& h, uint64_t now) {
    SimResult& res = s.res;
    if (s.ox == 0 && s.oy == 0) {
      if (!h.out_user && res.framing_error.empty())
        res.framing_error = fmt::format("frame {}: first pixel without tuser", s.oframe);
      s.cur = OutImage(s.width, s.height);
      res.stats[s.oframe].first_out_cycle = now;
    } else if (h.out_user && res.framing_error.empty()) {
      res.framing_error = fmt::format("frame {}: tuser at x {} y {}", s.oframe, s.ox, s.oy);
    }
    if (h.out_last != (s.ox == s.width - 1) && res.framing_error.empty())
      res.framing_error = fmt::format("frame {}: tlast {} at x {} y {}", s.oframe, h.out_last, s.ox, s.oy);
    s.cur.at(s.ox, s.oy) = h.out_data;
    if (++s.ox < s.width) return;
    s.ox = 0;
    if (on_row) on_row(s.oframe, s.oy);
    if (++s.oy < s.height) return;
    s.oy = 0;
    res.stats[s.oframe].last_out_cycle = now;
    if (s.frames.out)
      s.frames.out(s.oframe, std::move(s.cur));
    else
      res.frames.push_back(std::move(s.cur));
    ++s.oframe;
    if (on_frame) on_frame(s.oframe, s.frames.count);
  }

  // Let the last object packet out, and finish an AXI4-Lite access in flight (the
  // host's operations for frames beyond the stream are dropped).
  void drain(RunState& s) {
    auto& t = tb_.top();
    t.s_axis_tvalid = 0;
    for (int n = 0; (n < 4 * 64 * 8 + 64 && s.res.object_packets.size() < s.frames.count) || agent_.busy(); ++n) {
      t.m_axis_obj_tready = 1;
      t.eval();
      agent_.sample();
      const Handshakes h = Handshakes::sample(t);
      tb_.tick();
      if (agent_.busy())
        host_done(
            s.host, s.hi, [&s](uint32_t st) { return s.started(st); }, s.res);
      take_obj(s, h);
    }
  }

  Testbench<Top>& tb_;
  AxilMaster<Top> axil_;
  AxilAgent<Top> agent_;
};

}  // namespace sm
