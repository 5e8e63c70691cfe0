// Randomized robustness test of the whole IP (sm_top, small configuration): a fixed-seed
// generator mixes well-formed frames with every stream fault class of docs/streams.md
// (short / long lines, too few / too many lines, missing / doubled sof, sof mid-line,
// tvalid gaps of any length, output back-pressure patterns, aresetn and soft reset mid
// frame, disabled frames) and with register faults (out-of-range sizes, thresholds,
// gains, offsets, wild rectification grids). docs/robustness.md describes the checks:
//  - progress: no deadlock (a handshake on some stream within a bound while input is
//    offered and the output is ready; every frame out within a bound after the input),
//  - output framing: every frame starts with tuser, every line ends with tlast, W x H,
//  - every output frame (faulty or not) is bit-exact with sm::run_pipeline run on the
//    image the stream rules of docs/streams.md make of the input (padding = 0 pixels),
//    the object packets too,
//  - ERR_FLAGS and ERR_CNT_* (read over AXI4-Lite) equal the faults the model of the
//    sequencer's rules (sm::Sequencer, model/seq.hpp) counted; register reads return
//    the documented clamp.
//
// Usage: tb_faults --scene <dir> [--steps N] [--seed S] [--no-soft-reset] [--reset-phases]
//   --no-soft-reset: no CONTROL.SOFT_RESET steps (aresetn steps instead)
//   --reset-phases: aresetn of 1..3 clocks at every phase against a long one (ResetPhases)
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "toolio/sm_io.hpp"
#include "pipeline.hpp"
#include "post.hpp"
#include "seq.hpp"
#include "sm_axil.hpp"
#include "sm_handshakes.hpp"
#include "sm_regmap.hpp"
#include "sm_regs_io.hpp"
#include SM_VTOP_H
#include "sm_block_test.hpp"

namespace {

using Top = SM_VTOP;

using Bench = sm::test::BlockTest<Top>;

// ERR_FLAGS bit order: the sequencer's faults (sm::SeqFault), then the two others.
constexpr int kOverflow = sm::kNumSeqFaults, kClamped = kOverflow + 1, kNumFlags = kClamped + 1;
const char* fault_name(int k) {
  if (k < sm::kNumSeqFaults) return sm::seq_fault_name(static_cast<sm::SeqFault>(k));
  return k == kOverflow ? "OUT_OVERFLOW" : "CLAMPED";
}

struct Pixel {
  uint16_t data = 0;  // {right, left}
  bool user = false, last = false;
  int gap = 0;  // idle cycles before the pixel is offered
};

// A frame as the IP must output it: the stream rules (sm::Sequencer) turn whatever
// arrived into W x H (sm::SeqFrame: size, input images, faulty, complete).
struct ExpFrame : sm::SeqFrame {
  sm::Regs regs;
  int id = 0;                                 // frames started since reset
  std::shared_ptr<sm::PipelineResult> model;  // computed once (frame or packet first)
  ExpFrame(int w_, int h_) : SeqFrame(w_, h_) {}
  const sm::PipelineResult& result(const sm::HwConfig& hw) {
    if (!model) model = std::make_shared<sm::PipelineResult>(sm::run_pipeline(left, right, hw, regs, false));
    return *model;
  }
};

// The sequencer's stream rules (docs/streams.md, "Stream faults"; sm::Sequencer,
// model/seq.hpp) fed with the accepted camera pixels in order. This keeps the frames
// they make, each with the host registers it latched, and counts the fault events.
class SeqModel : public sm::SeqSink {
 public:
  std::array<uint32_t, kNumFlags> cnt{};  // events since the last CLEAR_ERRORS (counters)
  std::array<uint32_t, kNumFlags> ev{};   // events since the flags were last cleared
  std::deque<ExpFrame> frames;            // started, not yet output
  sm::Regs host;                          // host copy of the registers
  bool enable = true;

  SeqModel() = default;
  SeqModel(const SeqModel&) = delete;  // seq_ reports to this object
  SeqModel& operator=(const SeqModel&) = delete;

  void reset(bool counters) {
    seq_.reset();
    next_id_ = 0;
    frames.clear();
    if (counters) {
      cnt.fill(0);
      ev.fill(0);
    }
  }
  void push(const Pixel& p) {
    seq_.push({p.data, p.user, p.last},
              {static_cast<uint16_t>(host.width), static_cast<uint16_t>(host.height), enable});
  }

 private:
  void frame_start(int width, int height) override {
    ExpFrame f(width, height);
    f.regs = host;
    f.id = next_id_++;
    frames.push_back(std::move(f));
  }
  void beat(int x, int y, uint16_t data, bool /*pad*/) override { frames.back().put(x, y, data); }
  void frame_end(bool faulty) override { frames.back().faulty = faulty; }
  void fault(sm::SeqFault f) override {
    ++cnt[sm::seq_fault_bit(f)];
    ++ev[sm::seq_fault_bit(f)];
  }

  sm::Sequencer seq_{*this};
  int next_id_ = 0;
};

// Output back-pressure patterns.
enum class Ready { kAlways, kRandom, kBursty, kSlow };

class FaultTb {
 public:
  FaultTb(Bench& t, const sm::HwConfig& hw, uint32_t seed)
      : hw_(hw), t_(t), rng_(seed), axil_(tb_.top(), [this] { cycle(); }) {}

  sm::AxilMaster<Top>& axil() { return axil_; }
  SeqModel& model() { return model_; }
  std::mt19937& rng() { return rng_; }
  uint64_t cycles() const { return tb_.cycles(); }
  int frames_out() const { return frames_out_; }
  int clean_out() const { return clean_out_; }
  int faulty_out() const { return faulty_out_; }
  int recovered() const { return recovered_; }
  int soft_frames() const { return soft_frames_; }
  size_t queued() const { return cam_.size(); }
  void set_ready(Ready r) { ready_ = r; }
  void set_gap_percent(int p) { gap_percent_ = p; }

  void queue(const std::vector<Pixel>& px) { cam_.insert(cam_.end(), px.begin(), px.end()); }
  // The camera is reset with the core: its queue is dropped.
  void clear_camera() { cam_.clear(); }
  Top& top() { return tb_.top(); }
  // Same generator state from here on (a reset-phase trial replays a run exactly).
  void reseed(uint32_t s) {
    rng_.seed(s);
    burst_left_ = 0;
    burst_ready_ = true;
  }
  // Records what the core shows from now on (nullptr stops): a line per change of the
  // three TVALID / TREADY outputs and per handshake on either output, each with its
  // clock counted from here.
  void set_trace(std::vector<std::string>* t) {
    trace_ = t;
    trace_start_ = tb_.cycles();
    trace_sig_ = ~0u;
  }
  void note(const std::string& s) {
    if (trace_) trace_->push_back(fmt::format("c{} {}", tb_.cycles() - trace_start_, s));
  }

  // One clock: camera, output sinks, checks.
  void cycle() {
    auto& t = tb_.top();
    t.aresetn = in_reset_ ? 0 : 1;
    bool present = false;
    if (!cam_.empty() && !paused_) {
      Pixel& p = cam_.front();
      if (p.gap > 0) {
        --p.gap;
      } else if (!(gap_percent_ > 0 && static_cast<int>(rng_() % 100) < gap_percent_)) {
        present = true;
      }
      // Garbage on the data lines while tvalid is low.
      t.s_axis_tdata = present ? p.data : static_cast<uint16_t>(rng_());
      t.s_axis_tuser = present ? p.user : (rng_() & 1);
      t.s_axis_tlast = present ? p.last : (rng_() & 1);
    }
    t.s_axis_tvalid = present;
    bool ready = true;
    switch (ready_) {
      case Ready::kAlways:
        ready = true;
        break;
      case Ready::kRandom:
        ready = rng_() % 100 >= 40;
        break;
      case Ready::kSlow:
        ready = rng_() % 100 < 10;
        break;
      case Ready::kBursty:
        if (burst_left_ == 0) {
          burst_ready_ = !burst_ready_;
          burst_left_ = 1 + static_cast<int>(rng_() % (burst_ready_ ? 400 : 1500));
        }
        --burst_left_;
        ready = burst_ready_;
        break;
    }
    if (force_ready_) ready = true;
    if (hold_low_) ready = false;
    t.m_axis_tready = ready;
    t.m_axis_obj_tready = force_ready_ || rng_() % 100 >= 20;
    t.eval();
    const sm::Handshakes h = sm::Handshakes::sample(t);
    check_protocol(t, ready);
    // A pixel accepted while the core is in reset (aresetn low now or in the previous
    // clock: the core's reset is registered) is lost.
    const bool lost = in_reset_ || reset_prev_;
    const bool lost_now = in_reset_;
    reset_prev_ = in_reset_;
    tb_.tick();

    if (h.in) {
      Pixel p = cam_.front();
      cam_.pop_front();
      if (!lost) model_.push(p);
    }
    // The sinks are reset by the same aresetn: nothing is taken while it is low.
    if (h.out && !lost_now) out_beat(h.out_data, h.out_user, h.out_last);
    if (t.m_axis_obj_tvalid && pkt_.empty() && !hdr_seen_ && !lost_now) {
      hdr_seen_ = true;
      hdr_cycle_ = tb_.cycles();
    }
    if (trace_) {
      const unsigned sig = (t.m_axis_tvalid ? 1u : 0u) | (t.m_axis_obj_tvalid ? 2u : 0u) | (t.s_axis_tready ? 4u : 0u);
      if (sig != trace_sig_)
        note(
            fmt::format("m_axis_tvalid {} m_axis_obj_tvalid {} s_axis_tready {}", sig & 1u, (sig >> 1) & 1u, sig >> 2));
      trace_sig_ = sig;
      if (h.out) note(fmt::format("m_axis 0x{:08x} tuser {} tlast {}", h.out_data, h.out_user, h.out_last));
      if (h.obj) note(fmt::format("m_axis_obj 0x{:08x} tlast {}", h.obj_data, h.obj_last));
    }
    if (h.obj && !lost_now) {
      pkt_.push_back(h.obj_data);
      if (h.obj_last) {
        check_packet();
        pkt_.clear();
        hdr_seen_ = false;
      }
    }
    // Progress: with input offered and the output ready, some stream must move.
    if ((present && ready && !h.in && !h.out) && !in_reset_) {
      if (static_cast<uint64_t>(++stuck_) > kStuckBound * fold_) {
        t_.check(false, fmt::format("no progress for {} cycles at cycle {} (input offered, output ready)", kStuckBound,
                                    tb_.cycles()));
        throw std::runtime_error("deadlock");
      }
    } else if (h.in || h.out) {
      stuck_ = 0;
    }
  }

  // Runs until the camera queue is empty.
  void run_camera() {
    const uint64_t start = tb_.cycles();
    while (!cam_.empty()) {
      cycle();
      if (tb_.cycles() - start > 2000000ull * fold_) throw std::runtime_error("camera queue never drained");
    }
  }

  // Camera idle and the output ready until nothing has moved for a while: every accepted
  // pixel has been through the sequencer (the counters are final) and whatever the
  // pipeline can push out is out.
  // Bounds are in beats: a folded datapath takes F = DISP / PU clocks per beat.
  void drain(int min_cycles = 800) {
    paused_ = true;
    force_ready_ = true;
    const uint64_t start = tb_.cycles();
    uint64_t last_move = start;
    int seen = beats_;
    while (tb_.cycles() - start < static_cast<uint64_t>(min_cycles) * fold_ ||
           tb_.cycles() - last_move < 400ull * fold_) {
      cycle();
      if (beats_ != seen) {
        seen = beats_;
        last_move = tb_.cycles();
      }
      if (tb_.cycles() - start > 100000ull * fold_) throw std::runtime_error("output never went quiet");
    }
    paused_ = false;
    force_ready_ = false;
  }

  // Every closed frame must come out within a bound once the camera is idle (flush rows).
  void expect_all_out() {
    drain(3000);
    size_t pending = 0;
    for (const auto& f : model_.frames)
      if (f.complete()) ++pending;
    t_.check(pending == 0, fmt::format("{} complete frames still inside the core after the flush", pending));
  }

  void areset(int len) {
    in_reset_ = true;
    axil_.idle();
    // The sinks leave reset with the core: whatever the core offers after the reset
    // must be the start of a new frame / packet.
    out_reset();
    pre_.clear();
    pre_pkts_.clear();
    model_.reset(true);
    for (int i = 0; i < len; ++i) cycle();
    in_reset_ = false;
    cycle();
    model_.reset(true);
    model_.host = sm::Regs::defaults(hw_);
    model_.host.width = hw_.max_width;
    model_.host.height = hw_.max_height;
    model_.enable = true;
    clamped_ = false;
    out_reset();
  }
  // After a soft reset the core is back to its post-reset state except the registers and
  // the outputs, whose sinks are not reset: the frame the sink is receiving (it took the
  // frame's tuser beat, or is offered it) is completed -- the pixels the core had, then
  // invalid 0 words -- and an object packet in progress is sent whole; every other frame
  // accepted before it is abandoned (docs/streams.md, "Soft reset"). Callers keep the
  // output still around the reset (tready low, or a drained core), so the sink's state
  // now is its state when the pulse reaches the core.
  void after_soft_reset() {
    const auto& t = tb_.top();
    pre_.clear();
    if ((in_frame_ || (t.m_axis_tvalid && t.m_axis_tuser)) && !model_.frames.empty())
      pre_.push_back(model_.frames.front());
    pre_pkts_.clear();
    for (auto& f : model_.frames)
      if (f.complete() && f.id >= next_pkt_) pre_pkts_.push_back(sm::object_packet(f.result(hw_).objects, false));
    for (int id = next_pkt_; id < out_id_; ++id) pre_pkts_.push_back(done_pkts_[id % kKeep]);
    soft_cycle_ = tb_.cycles();
    model_.reset(false);
    next_pkt_ = 0;
    out_id_ = 0;
    // The pulse reaches the core two clocks after the write response; a pixel offered
    // before that would be lost in the reset of the input FIFO.
    paused_ = true;
    for (int i = 0; i < 4; ++i) cycle();
    paused_ = false;
  }
  void pause(bool p) { paused_ = p; }
  void hold_low(bool h) { hold_low_ = h; }
  // Runs until the disparity output (or the object stream) offers a beat; false if the
  // camera queue ran dry first.
  bool run_until_valid(bool obj) {
    for (int i = 0; i < 400000; ++i) {
      cycle();
      auto& t = tb_.top();
      if (obj ? t.m_axis_obj_tvalid : t.m_axis_tvalid) return true;
      if (cam_.empty() && i > 20000) return false;
    }
    return false;
  }
  bool& clamped() { return clamped_; }

  // Compares ERR_FLAGS / ERR_CNT_* with the model (call after drain()).
  void check_errors(const std::string& when) {
    uint32_t flags = axil_.read(sm::regmap::kERR_FLAGS);
    const uint32_t line = axil_.read(sm::regmap::kERR_CNT_LINE);
    const uint32_t sof = axil_.read(sm::regmap::kERR_CNT_SOF);
    const uint32_t rows = axil_.read(sm::regmap::kERR_CNT_ROWS);
    const uint32_t out = axil_.read(sm::regmap::kERR_CNT_OUT);
    const std::array<uint32_t, 7> got = {line & 0xffff, line >> 16, sof & 0xffff, sof >> 16,
                                         rows & 0xffff, rows >> 16, out & 0xffff};
    for (int k = 0; k < 7; ++k) {
      const uint32_t want = std::min<uint32_t>(model_.cnt[k], 0xffff);
      t_.check(got[k] == want, fmt::format("{}: ERR_CNT {} = {}, expected {}", when, fault_name(k), got[k], want));
      const bool fl = (flags >> k) & 1u;
      t_.check(fl == (model_.ev[k] > 0),
               fmt::format("{}: ERR_FLAGS.{} = {}, expected {}", when, fault_name(k), fl, model_.ev[k] > 0));
      fault_total_[k] += model_.ev[k];
    }
    t_.check(((flags >> kClamped) & 1u) == (clamped_ ? 1u : 0u),
             fmt::format("{}: ERR_FLAGS.CLAMPED = {}, expected {}", when, (flags >> kClamped) & 1u, clamped_));
    // Alternate the two ways of clearing.
    if (rng_() & 1) {
      axil_.write(sm::regmap::kCONTROL, control_word() | (1u << sm::regmap::kCONTROL_CLEAR_ERRORS_LSB));
      flags = axil_.read(sm::regmap::kERR_FLAGS);
      t_.check(flags == 0, fmt::format("{}: ERR_FLAGS 0x{:x} after CLEAR_ERRORS", when, flags));
      t_.check(axil_.read(sm::regmap::kERR_CNT_LINE) == 0 && axil_.read(sm::regmap::kERR_CNT_ROWS) == 0,
               when + ": counters cleared by CLEAR_ERRORS");
      model_.cnt.fill(0);
    } else {
      axil_.write(sm::regmap::kERR_FLAGS, 0xff);
      flags = axil_.read(sm::regmap::kERR_FLAGS);
      t_.check(flags == 0, fmt::format("{}: ERR_FLAGS 0x{:x} after writing 1s", when, flags));
      t_.check(axil_.read(sm::regmap::kERR_CNT_LINE) == ((got[1] << 16) | got[0]),
               when + ": writing ERR_FLAGS keeps the counters");
    }
    model_.ev.fill(0);
    clamped_ = false;
  }
  uint32_t control_word() const { return model_.enable ? (1u << sm::regmap::kCONTROL_ENABLE_LSB) : 0u; }
  const std::array<uint64_t, kNumFlags>& fault_total() const { return fault_total_; }

 private:
  // AXI4-Stream rules seen from the sinks (independent of the RTL's own assertions):
  // TVALID low in the clock after an edge that sampled aresetn low; once TVALID is high
  // it stays high with the same payload until the handshake unless aresetn intervenes;
  // tuser / tlast only with TVALID.
  void check_protocol(const Top& t, bool ready) {
    const bool ov = t.m_axis_tvalid, objv = t.m_axis_obj_tvalid;
    const uint64_t beat =
        uint64_t{t.m_axis_tdata} | (t.m_axis_tuser ? 1ull << 32 : 0ull) | (t.m_axis_tlast ? 1ull << 33 : 0ull);
    const uint64_t obeat = t.m_axis_obj_tdata | (t.m_axis_obj_tlast ? 1ull << 32 : 0ull);
    auto fail = [&](const std::string& what) { t_.check(false, fmt::format("cycle {}: {}", tb_.cycles(), what)); };
    if (reset_prev_ && (ov || objv))
      fail(fmt::format("TVALID high in the clock after a reset edge (m_axis {}, m_axis_obj {})", ov, objv));
    if (wait_out_ && (!ov || beat != wait_beat_))
      fail(fmt::format("m_axis beat 0x{:09x} withdrawn or changed before tready (now valid {} 0x{:09x})", wait_beat_,
                       ov, beat));
    if (wait_obj_ && (!objv || obeat != wait_obeat_))
      fail(fmt::format("m_axis_obj beat 0x{:09x} withdrawn or changed before tready", wait_obeat_));
    if (!ov && (t.m_axis_tuser || t.m_axis_tlast)) fail("m_axis tuser/tlast without tvalid");
    if (!objv && t.m_axis_obj_tlast) fail("m_axis_obj tlast without tvalid");
    // aresetn low at this edge releases the beat (the sink is reset too).
    wait_out_ = !in_reset_ && ov && !ready;
    wait_beat_ = beat;
    wait_obj_ = !in_reset_ && objv && !t.m_axis_obj_tready;
    wait_obeat_ = obeat;
  }

  void out_reset() {
    ox_ = oy_ = 0;
    in_frame_ = false;
    hdr_seen_ = false;
    wait_out_ = wait_obj_ = false;
    pkt_.clear();
    next_pkt_ = 0;
    out_id_ = 0;
  }

  void out_beat(uint32_t d, bool user, bool last) {
    ++beats_;
    if (!in_frame_) {
      if (!t_.check(user, fmt::format("output frame {}: first beat without tuser", frames_out_))) {
        return;
      }
      if (model_.frames.empty() && pre_.empty()) {
        t_.check(false, fmt::format("output frame {} started but no input frame is pending", frames_out_));
        return;
      }
      in_frame_ = true;
      ox_ = oy_ = 0;
      const ExpFrame& e = pre_.empty() ? model_.frames.front() : pre_.front();
      cur_ = sm::OutImage(e.w, e.h);
    } else {
      t_.check(!user, fmt::format("output frame {}: tuser at x {} y {}", frames_out_, ox_, oy_));
    }
    ExpFrame& f = pre_.empty() ? model_.frames.front() : pre_.front();
    t_.check(last == (ox_ == f.w - 1),
             fmt::format("output frame {}: tlast {} at x {} y {} (width {})", frames_out_, last, ox_, oy_, f.w));
    cur_.at(ox_, oy_) = d;
    if (++ox_ < f.w) return;
    ox_ = 0;
    if (++oy_ < f.h) return;
    in_frame_ = false;
    oy_ = 0;
    const int w = f.w, h = f.h;
    if (!pre_.empty() && pre_frame_done()) return;
    if (model_.frames.empty() || model_.frames.front().w != w || model_.frames.front().h != h) {
      t_.check(false, fmt::format("output frame {} ({}x{}) is none of the pending frames", frames_out_, w, h));
      return;
    }
    out_frame_done(model_.frames.front());
  }

  // The sink's frame at a soft reset: equal to its model up to some pixel k, invalid 0
  // words from k on (k = W x H when the core had the whole frame).
  bool pre_frame_done() {
    ExpFrame& f = pre_.front();
    const auto& m = f.result(hw_);
    const int n = f.w * f.h;
    int k = 0;
    while (k < n && m.out.at(k % f.w, k / f.w) == cur_.at(k % f.w, k / f.w)) ++k;
    int bad = 0;
    for (int i = k; i < n; ++i) bad += cur_.at(i % f.w, i / f.w) != 0;
    t_.check(bad == 0, fmt::format("output frame {} at a soft reset: model up to pixel {}, then {} of {} pixels not 0",
                                   frames_out_, k, bad, n - k));
    if (verbose_) fmt::print("  out frame at a soft reset: {} of {} pixels from the model\n", k, n);
    ++frames_out_;
    ++soft_frames_;
    pre_.clear();
    return true;
  }

  void out_frame_done(ExpFrame& f) {
    if (!t_.check(f.complete(), fmt::format("output frame {} complete before its input", frames_out_))) {
      model_.frames.pop_front();
      return;
    }
    const auto& m = model_.frames.front().result(hw_);
    int n = 0;
    for (int y = 0; y < f.h; ++y)
      for (int x = 0; x < f.w; ++x)
        if (m.out.at(x, y) != cur_.at(x, y) && n++ == 0)
          fmt::print("first mismatch: output frame {} ({}x{}, {}) x {} y {}: expected 0x{:08x} got 0x{:08x}\n",
                     frames_out_, f.w, f.h, f.faulty ? "faulty input" : "well-formed input", x, y, m.out.at(x, y),
                     cur_.at(x, y));
    t_.check(n == 0, fmt::format("output frame {} bit-exact ({} pixels differ)", frames_out_, n));
    if (f.faulty) {
      ++faulty_out_;
    } else {
      ++clean_out_;
      if (prev_faulty_) ++recovered_;
    }
    prev_faulty_ = f.faulty;
    done_pkts_[f.id % kKeep] = sm::object_packet(m.objects, false);
    out_id_ = f.id + 1;
    if (verbose_)
      fmt::print("  out frame id {} {}x{} {} at cycle {}\n", f.id, f.w, f.h, f.faulty ? "faulty" : "ok", tb_.cycles());
    ++frames_out_;
    model_.frames.pop_front();
  }

  void check_packet() {
    // A packet offered before the soft reset reached the core (its pulse is two clocks
    // after the write response, and a list being published may still load) belongs to a
    // frame from before it.
    if (soft_cycle_ && hdr_cycle_ <= soft_cycle_ + 4) {
      bool found = false;
      while (!pre_pkts_.empty() && !found) {
        found = pre_pkts_.front() == pkt_;
        pre_pkts_.pop_front();
      }
      t_.check(found, fmt::format("object packet ({} words) in progress at a soft reset matches a frame before it",
                                  pkt_.size()));
      return;
    }
    pre_pkts_.clear();
    // Packet n belongs to frame n since reset; it may leave before the frame's last pixel.
    const int id = next_pkt_++;
    for (auto& f : model_.frames)
      if (f.id == id) {
        if (!t_.check(f.complete(), fmt::format("object packet of frame {} before its input was complete", id))) return;
        const auto want = sm::object_packet(f.result(hw_).objects, false);
        t_.check(pkt_ == want,
                 fmt::format("object packet of frame {} ({} words, expected {})", id, pkt_.size(), want.size()));
        return;
      }
    if (id < out_id_) {
      t_.check(pkt_ == done_pkts_[id % kKeep], fmt::format("object packet of frame {} (after the frame)", id));
      return;
    }
    t_.check(false, fmt::format("object packet {} without a frame", id));
  }

  static constexpr int kStuckBound = 6000;
  sm::HwConfig hw_;
  uint64_t fold_ = static_cast<uint64_t>(hw_.clocks_per_beat());  // clocks per beat
  Bench& t_;  // the kernel: the model, its coverage, the pass/fail count
  sm::Testbench<Top>& tb_{t_.tb()};
  std::mt19937 rng_;
  sm::AxilMaster<Top> axil_;
  SeqModel model_;
  std::deque<Pixel> cam_;
  bool paused_ = false, force_ready_ = false, in_reset_ = false, reset_prev_ = false, hold_low_ = false;
  // sink-side protocol state
  bool wait_out_ = false, wait_obj_ = false;
  uint64_t wait_beat_ = 0;
  uint64_t wait_obeat_ = 0;
  bool hdr_seen_ = false;
  uint64_t hdr_cycle_ = 0, soft_cycle_ = 0;
  // frames and packets from before the last soft reset that may still come out
  std::deque<ExpFrame> pre_;
  std::deque<std::vector<uint32_t>> pre_pkts_;
  Ready ready_ = Ready::kAlways;
  int burst_left_ = 0;
  bool burst_ready_ = true;
  int gap_percent_ = 0;
  int stuck_ = 0;
  // output side
  bool in_frame_ = false;
  int ox_ = 0, oy_ = 0;
  sm::OutImage cur_;
  static constexpr int kKeep = 64;
  std::array<std::vector<uint32_t>, kKeep> done_pkts_;  // packets of output frames
  int next_pkt_ = 0, out_id_ = 0;
  std::vector<uint32_t> pkt_;
  int beats_ = 0, frames_out_ = 0, clean_out_ = 0, faulty_out_ = 0, recovered_ = 0, soft_frames_ = 0;
  bool prev_faulty_ = false;
  std::vector<std::string>* trace_ = nullptr;
  uint64_t trace_start_ = 0;
  unsigned trace_sig_ = 0;

 public:
  bool verbose_ = getenv("SM_VERBOSE") != nullptr;
  bool clamped_ = false;
  std::array<uint64_t, kNumFlags> fault_total_{};
};

// Camera pixels of a W x H frame cut from the scene at (ox, oy).
std::vector<Pixel> frame_pixels(const sm::Image8& l, const sm::Image8& r, int w, int h, int ox, int oy) {
  std::vector<Pixel> px;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Pixel p;
      p.data = static_cast<uint16_t>(l.at(ox + x, oy + y) | (r.at(ox + x, oy + y) << 8));
      p.user = (x == 0 && y == 0);
      p.last = (x == w - 1);
      px.push_back(p);
    }
  return px;
}

// The scalar run-time registers (no grids, no CONTROL): what a host changes per frame.
void write_scalars(Bench& t, sm::AxilMaster<Top>& axil, const sm::Regs& r) {
  for (const sm::RegWord& w : sm::register_words(r))
    t.check(axil.write(w.addr, w.value) == 0, fmt::format("{} write accepted", w.name));
}

uint32_t clamp_u(uint32_t v, uint32_t lo, uint32_t hi) { return std::min(std::max(v, lo), hi); }

// The documented reset value of a register (rtl/regmap.json): every field at its reset
// value, signed fields sign-extended (read-only counters and flags reset to 0).
uint32_t reset_word(const sm::regmap::Reg& r, const sm::HwConfig& hw) {
  uint32_t v = 0;
  for (int i = 0; i < r.num_fields; ++i) {
    const auto& f = sm::regmap::fields()[static_cast<size_t>(r.first_field + i)];
    const auto x = static_cast<uint32_t>(f.reset.eval(hw));
    v |= f.is_signed ? x : (x << f.lsb) & f.mask();
  }
  return v;
}

// aresetn pulses of 1, 2 and 3 clocks at every phase of a frame, an object packet, a
// register access and a full input FIFO (issue 40): the core must come out of each exactly
// as out of a long (16-clock) reset at the same point. Every trial starts from the same
// state (long reset, registers, generator seed), runs to its phase, pulls aresetn, then
// records everything the core shows afterwards: both TVALIDs and s_axis_tready clock by
// clock, every register read back, a frame and its object packet, and the status, error
// and object-list registers after it. The records of the short pulses must equal the long
// reset's line by line; on top, each is checked against the documented reset state and
// the model (the frame and packet bit-exact, ERR_* equal to the model's count).
class ResetPhases {
 public:
  ResetPhases(Bench& t, FaultTb& tb, const sm::HwConfig& hw, const sm::Image8& l, const sm::Image8& r)
      : t_(t), tb_(tb), hw_(hw), l_(l), r_(r) {}

  void run() {
    // The events the phases are measured from, found on a run without reset.
    const Events ev = scan();
    const Events full = scan_full();
    fmt::print(
        "reset phases: first pixel at clock {}, mid-frame pixel {}, last input pixel {}, last output beat {}, object "
        "packet offered {}, input FIFO full {}\n",
        ev.first_in, ev.mid_in, ev.last_in, ev.last_out, ev.obj_valid, full.fifo_full);
    std::vector<Case> cases;
    auto add = [&](const std::string& name, Scn scn, int64_t at) { cases.push_back({name, scn, at}); };
    // The first pixel: with tuser it starts a frame (STATUS.FRAME_COUNT), without it
    // is a missing start of frame (ERR_FLAGS.MISSING_SOF, ERR_CNT_SOF).
    // The sequencer takes the pixel from the input FIFO a few clocks after the handshake.
    for (int d = -1; d <= 3; ++d) add(fmt::format("frame start (tuser pixel) {:+d}", d), Scn::kFrame, ev.first_in + d);
    for (int d = -1; d <= 3; ++d) add(fmt::format("pixel without tuser {:+d}", d), Scn::kNoSof, ev.first_in + d);
    for (int d = -1; d <= 0; ++d) add(fmt::format("mid-frame input {:+d}", d), Scn::kFrame, ev.mid_in + d);
    for (int d = -1; d <= 1; ++d) add(fmt::format("last input pixel {:+d}", d), Scn::kFrame, ev.last_in + d);
    add("frame tail (flush rows)", Scn::kFrame, (ev.last_in + ev.last_out) / 2);
    for (int d = -2; d <= 0; ++d) add(fmt::format("last output beat {:+d}", d), Scn::kFrame, ev.last_out + d);
    // The list is published at the edge that raises m_axis_obj_tvalid: aresetn low at
    // that edge is "publish 0", one and two clocks earlier "-1", "-2".
    for (int d = -2; d <= 0; ++d) add(fmt::format("object list publish {:+d}", d), Scn::kFrame, ev.obj_valid + d);
    for (int d = 1; d <= 4; ++d) add(fmt::format("object packet mid-send +{}", d), Scn::kFrame, ev.obj_valid + d);
    for (int d = 0; d <= 1; ++d) add(fmt::format("input FIFO full +{}", d), Scn::kFull, full.fifo_full + d);
    for (int d = 0; d <= 4; ++d) add(fmt::format("AXI4-Lite write in flight +{}", d), Scn::kWrite, d);
    for (int d = 0; d <= 4; ++d) add(fmt::format("AXI4-Lite soft-reset write in flight +{}", d), Scn::kSoftWrite, d);
    for (int d = 0; d <= 5; ++d) add(fmt::format("AXI4-Lite read in flight +{}", d), Scn::kRead, d);
    int differ = 0;
    for (const Case& c : cases) {
      const std::vector<std::string> ref = trial(c, kLong);
      for (int len = 1; len <= 3; ++len) {
        const std::vector<std::string> got = trial(c, len);
        differ += !t_.check(same(ref, got, c.name, len),
                            fmt::format("{}: state after a {}-clock aresetn equals the state after a {}-clock one",
                                        c.name, len, kLong));
      }
    }
    fmt::print("reset phases: {} phases x aresetn of 1, 2, 3 clocks against {} clocks, {} differ\n", cases.size(),
               kLong, differ);
  }

 private:
  static constexpr int kLong = 16;
  enum class Scn { kFrame, kNoSof, kFull, kWrite, kSoftWrite, kRead };
  struct Case {
    std::string name;
    Scn scn;
    int64_t at;  // clocks from the trial's start to the first edge with aresetn low
  };
  struct Events {
    int64_t first_in = -1, mid_in = -1, last_in = -1, last_out = -1, obj_valid = -1, fifo_full = -1;
  };

  sm::Regs regs() const {
    sm::Regs r = sm::Regs::defaults(hw_);
    r.width = 24;
    r.height = 16;
    r.obj_min_pixels = 4;  // a few objects in the packet
    r.grid_l = r.grid_r = sm::RectGrid{};
    return r;
  }
  std::vector<Pixel> frame(int ox, int oy) const { return frame_pixels(l_, r_, 24, 16, ox, oy); }
  void program() {
    tb_.pause(true);
    sm::write_registers(tb_.axil(), regs(), hw_);
    tb_.model().host = regs();
    tb_.model().enable = true;
    tb_.pause(false);
  }
  // The same state for every trial: a long reset, the registers, the generator.
  void start() {
    tb_.clear_camera();
    tb_.hold_low(false);
    tb_.set_ready(Ready::kAlways);
    tb_.set_gap_percent(0);
    tb_.areset(kLong);
    program();
    tb_.reseed(40);
  }
  void begin(Scn scn) {
    if (scn == Scn::kFrame || scn == Scn::kNoSof) {
      std::vector<Pixel> px = frame(5, 3);
      px[0].gap = 20;  // the core idle before the frame
      px[0].user = scn == Scn::kFrame;
      tb_.queue(px);
    }
    if (scn == Scn::kFull) {
      tb_.hold_low(true);  // the output stalls: the pipeline, then the input FIFO fill up
      for (int i = 0; i < 4; ++i) tb_.queue(frame(i, 2 * i));
    }
  }

  Events scan() {
    Events e;
    start();
    begin(Scn::kFrame);
    const size_t n = tb_.queued();
    const int before = tb_.frames_out();
    // (the object packet may leave before the frame's last pixel: the labeller reads the
    // words ahead of the output smoothing's two rows)
    for (int64_t c = 1; c < 400000 && (e.obj_valid < 0 || e.last_out < 0); ++c) {
      const size_t q = tb_.queued();
      tb_.cycle();
      if (q > tb_.queued() && q == n) e.first_in = c;
      if (q > tb_.queued() && q == n / 2) e.mid_in = c;
      if (q > tb_.queued() && q == 1) e.last_in = c;
      if (tb_.frames_out() > before && e.last_out < 0) e.last_out = c;
      if (tb_.top().m_axis_obj_tvalid && e.obj_valid < 0) e.obj_valid = c;
    }
    tb_.drain();
    if (e.first_in < 0 || e.mid_in < 0 || e.last_in < 0 || e.last_out < 0 || e.obj_valid < 0)
      throw std::runtime_error("reset phases: the frame's events were not all seen");
    return e;
  }
  Events scan_full() {
    Events e;
    start();
    begin(Scn::kFull);
    for (int64_t c = 1; c < 400000 && e.fifo_full < 0; ++c) {
      tb_.cycle();
      if (!tb_.top().s_axis_tready && tb_.queued() > 0) e.fifo_full = c;
    }
    if (e.fifo_full < 0) throw std::runtime_error("reset phases: the input FIFO never filled");
    return e;
  }

  // A register access left in flight (the master is reset with the core): started at the
  // trial's start, aresetn pulled `at` clocks later.
  void access(Scn scn, int64_t at) {
    sm::AxilAgent<Top> ag(tb_.top());
    if (scn == Scn::kWrite) ag.write(sm::regmap::kOCC, 77);
    if (scn == Scn::kSoftWrite)
      ag.write(sm::regmap::kCONTROL,
               (1u << sm::regmap::kCONTROL_ENABLE_LSB) | (1u << sm::regmap::kCONTROL_SOFT_RESET_LSB));
    if (scn == Scn::kRead) ag.read(sm::regmap::obj_header_addr());
    for (int64_t c = 0; c < at; ++c) {
      ag.sample();
      tb_.cycle();
      ag.update();
    }
    ag.abandon();
  }

  std::vector<std::string> trial(const Case& c, int len) {
    start();
    if (c.scn == Scn::kWrite || c.scn == Scn::kSoftWrite || c.scn == Scn::kRead) {
      access(c.scn, c.at);
    } else {
      begin(c.scn);
      for (int64_t i = 0; i < c.at - 1; ++i) tb_.cycle();
    }
    tb_.clear_camera();  // the camera is reset too
    const std::string when = fmt::format("{}, {}-clock aresetn", c.name, len);
    tb_.areset(len);
    tb_.hold_low(false);
    tb_.reseed(41);
    std::vector<std::string> rec;
    tb_.set_trace(&rec);
    probe(when);
    tb_.set_trace(nullptr);
    return rec;
  }

  // Everything the core shows after the reset, checked against the documented reset
  // state and the model, and recorded for the comparison.
  void probe(const std::string& when) {
    auto& axil = tb_.axil();
    // Nothing was offered since the reset: both outputs stay idle.
    tb_.pause(true);
    for (int i = 0; i < 64; ++i) {
      tb_.cycle();
      t_.check(!tb_.top().m_axis_tvalid && !tb_.top().m_axis_obj_tvalid,
               fmt::format("{}: no TVALID before any input (clock {} after the reset)", when, i));
    }
    for (const auto& reg : sm::regmap::registers()) {
      const uint32_t v = axil.read(reg.addr), want = reset_word(reg, hw_);
      tb_.note(fmt::format("{} = 0x{:08x}", reg.name, v));
      t_.check(v == want, fmt::format("{}: {} reads 0x{:x}, documented reset value 0x{:x}", when, reg.name, v, want));
    }
    const uint32_t hdr = axil.read(sm::regmap::obj_header_addr());
    tb_.note(fmt::format("OBJ_HEADER = 0x{:08x}", hdr));
    t_.check(hdr == 0, fmt::format("{}: OBJ_HEADER reads 0x{:x} (VALID {}, COUNT {}), no list since the reset", when,
                                   hdr, (hdr >> sm::regmap::kOBJ_HEADER_VALID_LSB) & 1u, hdr & 0xffu));
    tb_.pause(false);
    // A frame after the reset: bit-exact frame and packet (FaultTb checks them), its
    // count, no error.
    const int before = tb_.frames_out();
    program();
    tb_.queue(frame(2, 1));
    tb_.run_camera();
    tb_.drain(3000);
    t_.check(tb_.frames_out() == before + 1,
             fmt::format("{}: {} frames out after the reset, expected 1", when, tb_.frames_out() - before));
    for (uint32_t a :
         {sm::regmap::kSTATUS, sm::regmap::kERR_FLAGS, sm::regmap::kERR_CNT_LINE, sm::regmap::kERR_CNT_SOF,
          sm::regmap::kERR_CNT_ROWS, sm::regmap::kERR_CNT_OUT, sm::regmap::kIN_FIFO, sm::regmap::obj_header_addr()})
      tb_.note(fmt::format("after the frame: 0x{:03x} = 0x{:08x}", a, axil.read(a)));
    const uint32_t st = axil.read(sm::regmap::kSTATUS);
    t_.check((st & 0xffffu) == 1, fmt::format("{}: STATUS.FRAME_COUNT {} after one frame", when, st & 0xffffu));
    tb_.check_errors(when);
  }

  bool same(const std::vector<std::string>& ref, const std::vector<std::string>& got, const std::string& name,
            int len) const {
    for (size_t i = 0; i < std::max(ref.size(), got.size()); ++i) {
      const std::string a = i < ref.size() ? ref[i] : "(end)", b = i < got.size() ? got[i] : "(end)";
      if (a == b) continue;
      fmt::print("{}: after a {}-clock aresetn: {}\n{:>{}}  after a {}-clock aresetn: {}\n", name, len, b, "",
                 name.size(), kLong, a);
      return false;
    }
    return true;
  }

  Bench& t_;
  FaultTb& tb_;
  sm::HwConfig hw_;
  const sm::Image8& l_;
  const sm::Image8& r_;
};

}  // namespace

int main(int argc, char** argv) {
  Bench bench{"sm_top randomized robustness test"};
  std::string scene;
  int n_frames = 400;
  uint32_t seed = 20240611u;
  bool no_soft = false;
  bench.option("--scene", scene, "scene folder, at least MAX_WIDTH x MAX_HEIGHT").required();
  bench.option("--steps", n_frames, "input steps (a frame, faulty or not, and its recovery frame)");
  bench.option("--seed", seed, "random seed");
  bench.flag("--no-soft-reset", no_soft, "aresetn steps instead of CONTROL.SOFT_RESET");
  bool phases = false;
  bench.flag("--reset-phases", phases,
             "instead of the random mix: aresetn of 1, 2, 3 clocks at every phase against a long one");
  // a flood of one rule must not hide another
  bench.report_each_kind(20);
  if (auto rc = bench.parse(argc, argv)) return *rc;
  const bool soft_reset = !no_soft;
  try {
    const sm::HwConfig hw = sm::verilated_config();
    const sm::tools::Scene sc = sm::tools::load_scene(scene);
    const sm::Image8 sl = sm::tools::to_image8(sc.left), sr = sm::tools::to_image8(sc.right);
    if (sl.w < hw.max_width || sl.h < hw.max_height)
      throw std::runtime_error(fmt::format("{}: scene {}x{} smaller than the configuration {}x{}", scene, sl.w, sl.h,
                                           hw.max_width, hw.max_height));
    FaultTb tb(bench, hw, seed);
    if (phases) {
      ResetPhases(bench, tb, hw, sl, sr).run();
      return bench.finish("tb_faults --reset-phases");
    }
    auto& rng = tb.rng();
    auto& axil = tb.axil();
    using namespace sm::regmap;

    // Well-formed operating points (W >= DISP/2 + 3, H >= 16).
    const std::vector<std::pair<int, int>> sizes = {{24, 16}, {24, 16}, {24, 16}, {17, 16}, {32, 20}};
    int cur = 0;
    auto regs_for = [&](int w, int h) {
      sm::Regs r = sm::Regs::defaults(hw);
      r.width = w;
      r.height = h;
      r.grid_l = r.grid_r = sm::RectGrid{};  // identity for the active size
      return r;
    };
    auto program = [&](const sm::Regs& r) {
      tb.pause(true);
      sm::write_registers(axil, r, hw);
      tb.model().host = r;
      tb.model().enable = true;
      tb.pause(false);
    };
    tb.areset(8);
    program(regs_for(24, 16));

    auto W = [&] { return tb.model().host.width; };
    auto H = [&] { return tb.model().host.height; };
    auto good = [&] {
      const int w = W(), h = H();
      const int ox = static_cast<int>(rng() % (hw.max_width - w + 1));
      const int oy = static_cast<int>(rng() % (hw.max_height - h + 1));
      return frame_pixels(sl, sr, w, h, ox, oy);
    };
    auto idx = [&](int x, int y) { return static_cast<size_t>(y) * W() + x; };

    std::array<int, 24> injected{};
    const char* const kind_name[] = {"well-formed",
                                     "short line",
                                     "long line",
                                     "too few lines",
                                     "too many lines",
                                     "missing sof",
                                     "doubled sof",
                                     "sof mid-line",
                                     "long tvalid gap",
                                     "back-pressure burst",
                                     "aresetn mid-frame",
                                     "soft reset mid-frame",
                                     "frame while disabled",
                                     "size change",
                                     "register faults",
                                     "rectification grid faults",
                                     "truncated stream",
                                     "aresetn while valid",
                                     "soft reset, tready low",
                                     "registers every frame"};
    const int n_kinds = 20;

    for (int f = 0; f < n_frames; ++f) {
      // Per-frame stream character.
      tb.set_gap_percent(rng() % 4 == 0 ? static_cast<int>(rng() % 50) : 0);
      const int rp = static_cast<int>(rng() % 8);
      tb.set_ready(rp < 3 ? Ready::kAlways : rp < 6 ? Ready::kRandom : rp < 7 ? Ready::kBursty : Ready::kSlow);

      int kind = (rng() % 100 < 35) ? 0 : 1 + static_cast<int>(rng() % (n_kinds - 1));
      if ((kind == 11 || kind == 18) && !soft_reset) kind = kind == 11 ? 10 : 17;
      ++injected[kind];
      if (tb.verbose_) fmt::print("step {}: {} at cycle {}\n", f, kind_name[kind], tb.cycles());
      std::vector<Pixel> px = good();
      const int w = W(), h = H();
      switch (kind) {
        case 0:
          break;
        case 1: {  // short line: tlast early
          const int y = static_cast<int>(rng() % h), x = static_cast<int>(rng() % (w - 1));
          std::vector<Pixel> out;
          for (int yy = 0; yy < h; ++yy)
            for (int xx = 0; xx < w; ++xx) {
              if (yy == y && xx > x) continue;
              Pixel p = px[idx(xx, yy)];
              if (yy == y && xx == x) p.last = true;
              out.push_back(p);
            }
          px = out;
          break;
        }
        case 2: {  // long line: extra pixels before tlast (sometimes on the last line)
          const int y = (rng() & 1) ? h - 1 : static_cast<int>(rng() % h);
          const int extra = 1 + static_cast<int>(rng() % (2 * w));
          std::vector<Pixel> out;
          for (int yy = 0; yy < h; ++yy)
            for (int xx = 0; xx < w; ++xx) {
              Pixel p = px[idx(xx, yy)];
              if (yy == y && xx == w - 1) {
                p.last = false;
                out.push_back(p);
                for (int e = 0; e < extra; ++e) {
                  Pixel q;
                  q.data = static_cast<uint16_t>(rng());
                  q.last = (e == extra - 1);
                  out.push_back(q);
                }
                continue;
              }
              out.push_back(p);
            }
          px = out;
          break;
        }
        case 3:  // too few lines: the next frame's tuser comes early
          px.resize(static_cast<size_t>(w) * (1 + rng() % (h - 1)));
          break;
        case 4: {  // too many lines
          const int extra = 1 + static_cast<int>(rng() % 4);
          for (int e = 0; e < extra * w; ++e) {
            Pixel q;
            q.data = static_cast<uint16_t>(rng());
            q.last = (e % w == w - 1);
            px.push_back(q);
          }
          break;
        }
        case 5:  // missing sof: the whole frame without tuser (counts as MANY_LINES after a frame)
          px[0].user = false;
          break;
        case 6: {  // doubled sof: the camera restarts the frame after a few pixels
          const int k = 1 + static_cast<int>(rng() % (2 * w));
          std::vector<Pixel> out(px.begin(), px.begin() + k);
          out.insert(out.end(), px.begin(), px.end());
          px = out;
          break;
        }
        case 7: {  // sof mid-line: the frame is cut inside a line by the next frame
          const int y = static_cast<int>(rng() % h), x = 1 + static_cast<int>(rng() % (w - 1));
          px.resize(idx(x, y));
          break;
        }
        case 8:  // a long tvalid gap somewhere in the frame
          px[rng() % px.size()].gap = static_cast<int>(rng() % 20000);
          break;
        case 9:  // a long output stall
          tb.set_ready(Ready::kBursty);
          break;
        case 10: {  // aresetn mid-frame, the camera keeps going afterwards (mid-frame)
          const size_t cut = rng() % px.size();
          tb.queue(std::vector<Pixel>(px.begin(), px.begin() + cut));
          // Let part of it in, then pull the reset while the stream is still flowing.
          for (int i = 0, n = static_cast<int>(rng() % (2 * cut + 2)); i < n; ++i) tb.cycle();
          tb.areset(1 + static_cast<int>(rng() % 20));
          tb.pause(true);
          const sm::Regs keep = regs_for(w, h);
          program(keep);
          px.clear();  // the rest of the camera queue continues mid-frame
          break;
        }
        case 11: {  // soft reset mid-frame
          const size_t cut = 1 + rng() % (px.size() - 1);
          tb.queue(std::vector<Pixel>(px.begin(), px.begin() + cut));
          tb.run_camera();
          tb.drain();
          axil.write(kCONTROL, tb.control_word() | (1u << kCONTROL_SOFT_RESET_LSB));
          tb.after_soft_reset();
          px.assign(px.begin() + cut, px.end());  // rest of the frame: no tuser -> MISSING_SOF
          break;
        }
        case 12: {  // frames while disabled are dropped silently
          tb.run_camera();
          tb.drain();
          axil.write(kCONTROL, 0);
          tb.model().enable = false;
          tb.queue(px);
          tb.queue(good());
          tb.run_camera();
          tb.drain();
          axil.write(kCONTROL, 1u << kCONTROL_ENABLE_LSB);
          tb.model().enable = true;
          px = good();
          break;
        }
        case 13: {  // legal size change (flush rows of the old width first)
          tb.run_camera();
          tb.drain();
          cur = (cur + 1 + static_cast<int>(rng() % (sizes.size() - 1))) % static_cast<int>(sizes.size());
          program(regs_for(sizes[cur].first, sizes[cur].second));
          px = good();
          break;
        }
        case 14: {  // register faults: out-of-range values are clamped and flagged
          tb.run_camera();
          tb.drain();
          tb.check_errors(fmt::format("before register faults (frame {})", f));
          sm::Regs r = tb.model().host;
          struct Wr {
            uint32_t addr;
            uint32_t v;
          };
          std::vector<Wr> wr;
          const uint32_t big[] = {0u, 1u, 15u, 65u, 1000u, 0x10000u, 0xffffffffu, 0x80000000u};
          const uint32_t ws = big[rng() % 8], hs = big[rng() % 8];
          const bool size_fault = rng() % 3 == 0;
          uint32_t wv = size_fault ? ws : static_cast<uint32_t>(r.width);
          uint32_t hv = size_fault ? hs : static_cast<uint32_t>(r.height);
          const uint32_t occ = 200u + rng() % 1000u, gain = 900u + rng() % 2000u;
          const int32_t off = static_cast<int32_t>(rng() % 2000u) - 1000;
          const uint32_t near = rng() % 600u, tol = rng() % 600u, minpix = rng() % 0x20000u;
          bool expect_clamp = false;
          auto ck = [&](uint32_t addr, uint32_t v, uint32_t want, const char* name) {
            bench.check(axil.write(addr, v) == 0, fmt::format("{} write accepted", name));
            const uint32_t got = axil.read(addr);
            bench.check(got == want, fmt::format("{} write 0x{:x} reads 0x{:x}, expected 0x{:x}", name, v, got, want));
          };
          const uint32_t wc = clamp_u(wv, 16, static_cast<uint32_t>(hw.max_width));
          const uint32_t hc = clamp_u(hv, 16, static_cast<uint32_t>(hw.max_height));
          expect_clamp |= (wc != wv) || (hc != hv);
          ck(kWIDTH, wv, wc, "WIDTH");
          ck(kHEIGHT, hv, hc, "HEIGHT");
          r.width = static_cast<int>(wc);
          r.height = static_cast<int>(hc);
          ck(kOCC, occ, std::min(occ, 255u), "OCC");
          r.occ = static_cast<uint8_t>(std::min(occ, 255u));
          ck(kGAIN_L, gain, std::min(gain, 1023u), "GAIN_L");
          r.gain_l = static_cast<uint16_t>(std::min(gain, 1023u));
          const int32_t offc = std::min(std::max(off, -256), 255);
          ck(kOFFSET_R, static_cast<uint32_t>(off), static_cast<uint32_t>(offc), "OFFSET_R");
          r.offset_r = static_cast<int16_t>(offc);
          ck(kOBJ_NEAR, near, std::min(near, 255u), "OBJ_NEAR");
          r.obj_near = static_cast<uint8_t>(std::min(near, 255u));
          ck(kOBJ_TOL, tol, std::min(tol, 255u), "OBJ_TOL");
          r.obj_tol = static_cast<uint8_t>(std::min(tol, 255u));
          ck(kOBJ_MIN_PIXELS, minpix, std::min(minpix, 65535u), "OBJ_MIN_PIXELS");
          r.obj_min_pixels = static_cast<uint16_t>(std::min(minpix, 65535u));
          expect_clamp |= occ > 255 || gain > 1023 || off != offc || near > 255 || tol > 255 || minpix > 65535;
          // Bit fields ignore bits outside their fields (no clamp).
          ck(kFILTER_ENABLE, 0xfffffff0u | r.filter_enable, r.filter_enable, "FILTER_ENABLE");
          // Unmapped and read-only addresses answer SLVERR and change nothing.
          bench.check(axil.write(0x3c, 0x1234) == 2, "write to an unmapped address answers SLVERR");
          bench.check(axil.write(kSTATUS, 0xffffffffu) == 2, "write to STATUS answers SLVERR");
          unsigned resp = 0;
          axil.read(0x7ffc, &resp);
          bench.check(resp == 2, "read of an unmapped address answers SLVERR");
          // Identity grids for a new size (the old ones do not cover it).
          const sm::RectGrid idl = sm::RectGrid::identity(r.width, r.height);
          sm::write_grid(axil, hw, 0, 0, idl);
          sm::write_grid(axil, hw, 1, 0, idl);
          r.grid_l = r.grid_r = sm::RectGrid{};
          tb.model().host = r;
          if (expect_clamp) tb.clamped() = true;
          tb.check_errors(fmt::format("register faults (frame {})", f));
          px = good();
          tb.queue(px);
          px = good();
          // Back to a sane operating point afterwards.
          tb.queue(px);
          tb.run_camera();
          tb.drain();
          cur = 0;
          program(regs_for(sizes[0].first, sizes[0].second));
          px = good();
          break;
        }
        case 15: {  // wild / singular rectification grids (any Q.5 value is legal input)
          tb.run_camera();
          tb.drain();
          sm::Regs r = tb.model().host;
          for (sm::RectGrid* g : {&r.grid_l, &r.grid_r}) {
            *g = sm::RectGrid::identity(r.width, r.height);
            const int mode = static_cast<int>(rng() % 3);
            for (size_t i = 0; i < g->sx.size(); ++i) {
              if (mode == 0) {  // everything from one point (singular)
                g->sx[i] = static_cast<int16_t>(5 * 32);
                g->sy[i] = static_cast<int16_t>(3 * 32);
              } else if (mode == 1) {  // anything
                g->sx[i] = static_cast<int16_t>(rng());
                g->sy[i] = static_cast<int16_t>(rng());
              } else {  // extreme values
                g->sx[i] = (rng() & 1) ? INT16_MAX : INT16_MIN;
                g->sy[i] = (rng() & 1) ? INT16_MAX : INT16_MIN;
              }
            }
          }
          program(r);
          tb.queue(px);
          px = good();  // then identity grids again
          tb.run_camera();
          tb.drain();
          program(regs_for(w, h));
          break;
        }
        case 17: {  // aresetn of 1..4 clocks while an output offers a beat, tready high or low
          tb.queue(px);
          tb.queue(good());
          const bool obj = rng() % 3 == 0, low = rng() & 1;
          tb.hold_low(low);
          if (tb.run_until_valid(obj))
            for (int i = 0, n = static_cast<int>(rng() % 3); i < n; ++i) tb.cycle();
          tb.areset(1 + static_cast<int>(rng() % 4));
          tb.hold_low(false);
          program(regs_for(w, h));
          px.clear();  // the rest of the camera queue continues mid-frame
          break;
        }
        case 18: {  // soft reset while the output waits for tready
          tb.queue(px);
          tb.queue(good());
          tb.hold_low(true);
          tb.run_until_valid(false);
          for (int i = 0, n = static_cast<int>(rng() % 40); i < n; ++i) tb.cycle();
          tb.pause(true);
          axil.write(kCONTROL, tb.control_word() | (1u << kCONTROL_SOFT_RESET_LSB));
          tb.after_soft_reset();
          for (int i = 0, n = static_cast<int>(rng() % 60); i < n; ++i) tb.cycle();
          tb.hold_low(false);
          px.clear();  // the rest of the camera queue: no tuser -> MISSING_SOF
          break;
        }
        case 19: {  // new registers for every frame, written while the previous frame streams
          tb.run_camera();
          tb.drain();
          // Identity grids of the largest size: the identity of every smaller size is a
          // part of them (the grid row stride does not depend on the active size).
          const sm::RectGrid idmax = sm::RectGrid::identity(hw.max_width, hw.max_height);
          sm::write_grid(axil, hw, 0, 0, idmax);
          sm::write_grid(axil, hw, 1, 0, idmax);
          auto started = [&] { return axil.read(kSTATUS) & 0xffffu; };
          const int n = 3 + static_cast<int>(rng() % 4);
          for (int i = 0; i < n; ++i) {
            sm::Regs r = tb.model().host;
            if (rng() % 4 == 0) r.width = sizes[rng() % sizes.size()].first;  // a flush, then the new width
            if (rng() % 4 != 0) r.height = 16 + static_cast<int>(rng() % (hw.max_height - 15));
            r.gain_l = static_cast<uint16_t>(160 + rng() % 200);
            r.offset_l = static_cast<int16_t>(static_cast<int>(rng() % 61) - 30);
            r.offset_r = static_cast<int16_t>(static_cast<int>(rng() % 61) - 30);
            for (auto& c : r.sw_table) c = static_cast<uint8_t>(rng() & 3);
            r.occ = static_cast<uint8_t>(rng() % 40);
            r.filter_enable = static_cast<uint8_t>(rng() % 16);
            r.rect_enable = rng() & 1;
            r.obj_near = static_cast<uint8_t>(rng() % hw.disp);
            r.obj_tol = static_cast<uint8_t>(rng() % 4);
            r.obj_min_pixels = static_cast<uint16_t>(rng() % 80);
            // The frame queued before this one has started (its shadow copy is taken),
            // so these values are the next frame start's, while that frame is still in
            // the pipeline.
            const uint32_t n0 = started();
            write_scalars(bench, axil, r);
            tb.model().host = r;
            tb.queue(frame_pixels(sl, sr, r.width, r.height, static_cast<int>(rng() % (hw.max_width - r.width + 1)),
                                  static_cast<int>(rng() % (hw.max_height - r.height + 1))));
            for (int k = 0; k < 100000 && started() == n0; ++k) {
            }
            bench.check(started() != n0, "registers every frame: the frame started");
          }
          tb.run_camera();
          tb.drain();
          program(regs_for(W(), H()));
          px = good();
          break;
        }
        case 16: {  // the camera stops mid-frame for good (cable pulled), then restarts
          const size_t cut = 1 + rng() % (px.size() - 1);
          px.resize(cut);
          tb.queue(px);
          tb.run_camera();
          tb.drain(2000);
          px = good();  // next tuser completes the open frame with padding (FEW/EXTRA)
          break;
        }
      }
      tb.queue(px);
      // Follow a fault with a well-formed frame (the recovery frame).
      if (kind != 0) tb.queue(good());
      tb.run_camera();
      if (rng() % 6 == 0 || kind == 10 || kind == 11) {
        tb.drain();
        tb.check_errors(fmt::format("after frame {} ({})", f, kind_name[kind]));
      }
      if (f % 50 == 49)
        fmt::print("{} input steps, {} frames out ({} faulty, {} well-formed), {} cycles\n", f + 1, tb.frames_out(),
                   tb.faulty_out(), tb.clean_out(), tb.cycles());
    }
    // One last well-formed frame and the flush: every complete frame must be out.
    tb.queue(good());
    tb.run_camera();
    tb.expect_all_out();
    tb.check_errors("end");

    fmt::print("injected:");
    for (int k = 0; k < n_kinds; ++k) fmt::print(" {}={}", kind_name[k], injected[k]);
    fmt::print("\nfault events counted by the model and matched in ERR_CNT:");
    for (int k = 0; k < 7; ++k) fmt::print(" {}={}", fault_name(k), tb.fault_total()[k]);
    fmt::print(
        "\n{} frames out: {} from faulty input, {} well-formed ({} right after a fault), all compared "
        "bit-exactly, {} completed at a soft reset; {} cycles\n",
        tb.frames_out(), tb.faulty_out(), tb.clean_out(), tb.recovered(), tb.soft_frames(), tb.cycles());
    bench.check(tb.recovered() >= n_frames / 10,
                fmt::format("{} recovery frames (at least {})", tb.recovered(), n_frames / 10));
    for (int k = 0; k < 6; ++k)
      bench.check(tb.fault_total()[k] > 0, fmt::format("fault class {} exercised", fault_name(k)));
  } catch (const std::exception& e) {
    bench.fail(fmt::format("exception: {}", e.what()));
  }
  return bench.finish(fmt::format("tb_faults steps={} seed={}", n_frames, seed));
}
