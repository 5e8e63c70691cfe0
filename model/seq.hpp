// Input sequencer sm_seq (docs/streams.md, "Input sequencer" and "Stream faults"): the
// framing rules that turn whatever the camera sends into frames of exactly W x H real
// beats -- short lines padded with 0, the rest of long lines dropped, an early tuser
// completes the open frame with 0 pixels, pixels without a frame dropped up to the next
// tuser, whole frames dropped while disabled -- and the fault events they report.
//
// The model is the rules' outcome, not their timing: the camera pixels are taken in
// the order the sequencer pops them from its input FIFO, padding needs no input and
// drops need no output. Virtual (flush) rows, the width-change flush, ftag and the
// clock-by-clock beat register are timing and are not modelled; the block test
// (tests/tb_seq.cpp) checks them against the RTL.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sm_types.hpp"

namespace sm {

// Fault classes of the sequencer in the bit order of err_pulse and ERR_FLAGS
// (rtl/regmap.json; ERR_CNT_LINE / _SOF / _ROWS hold their counters in this order too).
enum class SeqFault : uint8_t {
  kShortLine = 0,   // tlast at x < W-1: the rest of the row is padded with 0
  kLongLine = 1,    // no tlast at x = W-1: the rest of the line is dropped
  kMissingSof = 2,  // pixels without tuser, no frame open, none completed since reset
  kExtraSof = 3,    // tuser at 0 < x inside a frame: the frame is completed with 0
  kFewLines = 4,    // tuser at x = 0, 0 < y < H: the missing rows are padded with 0
  kManyLines = 5,   // pixels without tuser after a complete frame: dropped
};
constexpr int kNumSeqFaults = 6;
// The fault's ERR_FLAGS bit, which is also its index in SeqFaultCounts.
constexpr size_t seq_fault_bit(SeqFault f) { return static_cast<size_t>(f); }
// Its field name in the register map ("SHORT_LINE", ...).
const char* seq_fault_name(SeqFault f);
// Events per class (one per err_pulse, not per dropped pixel), indexed by seq_fault_bit.
using SeqFaultCounts = std::array<uint32_t, kNumSeqFaults>;

// One camera pixel as the sequencer pops it from its input FIFO (s_axis_* of a handshake).
struct CamPixel {
  uint16_t data = 0;  // tdata = {right, left}
  bool user = false;  // tuser: start of frame
  bool last = false;  // tlast: end of line
};

// The sequencer's run-time inputs from the register file: the host copy of WIDTH /
// HEIGHT (latched at a frame start, 1..MAX_WIDTH / MAX_HEIGHT) and CONTROL.ENABLE.
struct SeqHost {
  uint16_t width = 0;
  uint16_t height = 0;
  bool enable = true;
};

// The sequencer's outputs, called in stream order. Every real beat of a frame is one
// beat() call: camera pixels and padding alike, so a frame gets exactly width x height
// of them, (0, 0) first, raster order; virtual rows are not reported.
class SeqSink {
 public:
  virtual ~SeqSink() = default;
  // frame_start: a tuser pixel opened a frame with the host values latched.
  virtual void frame_start(int /*width*/, int /*height*/) {}
  // One real beat of the open frame; data = {right, left}, 0 when pad.
  virtual void beat(int /*x*/, int /*y*/, uint16_t /*data*/, bool /*pad*/) {}
  // The open frame's last beat was emitted; faulty: its input broke a rule (short or
  // long line, early tuser), so it was padded or lost pixels.
  virtual void frame_end(bool /*faulty*/) {}
  // One fault event (err_pulse).
  virtual void fault(SeqFault /*f*/) {}
};

// The sequencer's rules, one camera pixel at a time.
class Sequencer {
 public:
  explicit Sequencer(SeqSink& out) : out_(out) {}
  // State after aresetn or CONTROL.SOFT_RESET: no frame open (an open one is abandoned
  // without padding), no frame completed yet (pixels without tuser are MISSING_SOF).
  void reset();
  // One camera pixel popped from the FIFO; host: the register file's host values while
  // the pixel is at the FIFO head (they matter only when it starts a frame). Throws
  // std::invalid_argument when a frame would start with a width or height of 0.
  void push(const CamPixel& p, const SeqHost& host);
  bool frame_open() const { return frame_; }

 private:
  void take(const CamPixel& p);        // a camera pixel into the open frame
  void emit(uint16_t data, bool pad);  // one real beat; closes the frame after its last
  void fault(SeqFault f, bool of_frame);

  SeqSink& out_;
  bool frame_ = false;        // a frame is open (mode M_FRAME)
  bool drop_line_ = false;    // long line: dropping up to tlast (or a tuser)
  bool dropping_ = false;     // dropping up to the next tuser (already reported)
  bool after_frame_ = false;  // a frame has completed since reset
  bool faulty_ = false;       // the open frame's input broke a rule
  uint16_t x_ = 0, y_ = 0;    // next beat's position in the open frame
  uint16_t w_ = 0, h_ = 0;    // the open frame's latched size
};

// A frame as the sequencer emits it: w x h, padding reads 0.
struct SeqFrame {
  int w = 0, h = 0;  // host width / height latched at the frame start
  Image8 left, right;
  int beats = 0;        // real beats emitted so far
  bool faulty = false;  // set at its last beat (SeqSink::frame_end)
  SeqFrame() = default;
  SeqFrame(int w_, int h_) : w(w_), h(h_), left(w_, h_, 0), right(w_, h_, 0) {}
  // Stores one beat (SeqSink::beat).
  void put(int x, int y, uint16_t data);
  bool complete() const { return beats == w * h; }
  uint16_t data(int x, int y) const { return static_cast<uint16_t>(left.at(x, y) | right.at(x, y) << 8); }
};

// A camera pixel with the host values the sequencer sees while it is at the FIFO head.
struct SeqInput {
  CamPixel px;
  SeqHost host;
};

struct SeqResult {
  std::vector<SeqFrame> frames;  // in order; the last one may be incomplete
  SeqFaultCounts faults{};
};

// The whole stream after reset through a Sequencer.
SeqResult seq_frames(const std::vector<SeqInput>& in);

}  // namespace sm
