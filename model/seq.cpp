// Input sequencer sm_seq: the framing rules (docs/streams.md, "Stream faults").
#include "seq.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "sm_regmap.hpp"  // generated from rtl/regmap.json

namespace sm {

// The fault bits are ERR_FLAGS' first fields, in the same order.
static_assert(regmap::kERR_FLAGS_SHORT_LINE_LSB == 0 && regmap::kERR_FLAGS_LONG_LINE_LSB == 1 &&
                  regmap::kERR_FLAGS_MISSING_SOF_LSB == 2 && regmap::kERR_FLAGS_EXTRA_SOF_LSB == 3 &&
                  regmap::kERR_FLAGS_FEW_LINES_LSB == 4 && regmap::kERR_FLAGS_MANY_LINES_LSB == 5,
              "SeqFault and the register map's ERR_FLAGS disagree");

const char* seq_fault_name(SeqFault f) {
  static const auto names = [] {
    std::array<std::string, kNumSeqFaults> n;
    const std::string reg = "ERR_FLAGS.";
    for (const auto& field : regmap::fields()) {
      const std::string name = field.name;
      if (name.compare(0, reg.size(), reg) == 0 && field.lsb < kNumSeqFaults)
        n[static_cast<size_t>(field.lsb)] = name.substr(reg.size());
    }
    return n;
  }();
  return names[seq_fault_bit(f)].c_str();
}

void Sequencer::reset() {
  frame_ = drop_line_ = dropping_ = after_frame_ = faulty_ = false;
  x_ = y_ = w_ = h_ = 0;
}

void Sequencer::fault(SeqFault f, bool of_frame) {
  if (of_frame) faulty_ = true;
  out_.fault(f);
}

void Sequencer::push(const CamPixel& p, const SeqHost& host) {
  // The rest of a long line is dropped up to its tlast; a tuser ends the drop and is
  // then taken like any other pixel.
  if (drop_line_) {
    if (!p.user) {
      drop_line_ = !p.last;
      return;
    }
    drop_line_ = false;
  }
  if (frame_) {
    if (!p.user) {
      take(p);
      return;
    }
    // tuser inside the open frame: the frame is completed with 0 beats (the rest of
    // the row and the missing rows), then the pixel starts the next one.
    fault(x_ == 0 ? SeqFault::kFewLines : SeqFault::kExtraSof, true);
    while (frame_) emit(0, true);
  }
  // Between frames.
  if (!p.user) {
    // Only the history tells a camera that starts mid-frame from one sending extra lines.
    if (!dropping_) fault(after_frame_ ? SeqFault::kManyLines : SeqFault::kMissingSof, false);
    dropping_ = true;
    return;
  }
  if (!host.enable) {  // disabled: the whole frame is dropped silently
    dropping_ = true;
    return;
  }
  if (host.width == 0 || host.height == 0) throw std::invalid_argument("sm::Sequencer: frame size 0");
  frame_ = true;
  dropping_ = false;
  faulty_ = false;
  x_ = y_ = 0;
  w_ = host.width;
  h_ = host.height;
  out_.frame_start(w_, h_);
  take(p);
}

void Sequencer::take(const CamPixel& p) {
  const bool last_col = x_ == w_ - 1;
  const bool short_line = p.last && !last_col;
  if (short_line) fault(SeqFault::kShortLine, true);
  if (!p.last && last_col) {  // the pixel is kept, the rest of the line dropped
    fault(SeqFault::kLongLine, true);
    drop_line_ = true;
  }
  emit(p.data, false);
  if (short_line)  // the rest of the row is padded with 0
    while (x_ != 0) emit(0, true);
}

void Sequencer::emit(uint16_t data, bool pad) {
  out_.beat(x_, y_, data, pad);
  if (x_ != w_ - 1) {
    ++x_;
    return;
  }
  x_ = 0;
  if (y_ != h_ - 1) {
    ++y_;
    return;
  }
  y_ = 0;
  frame_ = false;
  after_frame_ = true;
  out_.frame_end(faulty_);
}

void SeqFrame::put(int x, int y, uint16_t data) {
  left.at(x, y) = static_cast<uint8_t>(data & 0xff);
  right.at(x, y) = static_cast<uint8_t>(data >> 8);
  ++beats;
}

namespace {
// Keeps every frame and counts the faults.
class FrameCollector : public SeqSink {
 public:
  explicit FrameCollector(SeqResult& r) : r_(r) {}
  void frame_start(int width, int height) override { r_.frames.emplace_back(width, height); }
  void beat(int x, int y, uint16_t data, bool /*pad*/) override { r_.frames.back().put(x, y, data); }
  void frame_end(bool faulty) override { r_.frames.back().faulty = faulty; }
  void fault(SeqFault f) override { ++r_.faults[seq_fault_bit(f)]; }

 private:
  SeqResult& r_;
};
}  // namespace

SeqResult seq_frames(const std::vector<SeqInput>& in) {
  SeqResult r;
  FrameCollector out(r);
  Sequencer seq(out);
  for (const SeqInput& i : in) seq.push(i.px, i.host);
  return r;
}

}  // namespace sm
