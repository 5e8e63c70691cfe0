// Unit tests of the input sequencer's model (model/seq.hpp, docs/streams.md "Stream
// faults") against hand-written camera streams whose frames and fault events are worked
// out by hand from the rules: a 4 x 3 frame size throughout, pixel values that name their
// place in the stream, 0 for padding.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "seq.hpp"
#include "sm_regmap.hpp"

namespace {

using Rows = std::vector<std::vector<uint16_t>>;

// A camera stream built line by line, every pixel with the same host values.
struct Stream {
  sm::SeqHost host{4, 3, true};
  std::vector<sm::SeqInput> in;
  // One line: tuser on its first pixel when sof, tlast on its last one when last.
  Stream& line(const std::vector<uint16_t>& px, bool sof = false, bool last = true) {
    for (size_t i = 0; i < px.size(); ++i) in.push_back({{px[i], sof && i == 0, last && i + 1 == px.size()}, host});
    return *this;
  }
  // A well-formed 4 x 3 frame of the values first, first + 1, ...
  Stream& frame(uint16_t first) {
    for (int y = 0; y < 3; ++y) {
      const uint16_t v = static_cast<uint16_t>(first + 4 * y);
      line({v, static_cast<uint16_t>(v + 1), static_cast<uint16_t>(v + 2), static_cast<uint16_t>(v + 3)}, y == 0);
    }
    return *this;
  }
};

Rows rows(const sm::SeqFrame& f) {
  Rows r(static_cast<size_t>(f.h));
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) r[static_cast<size_t>(y)].push_back(f.data(x, y));
  return r;
}
const Rows kFrame1 = {{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}};  // Stream::frame(1)

sm::SeqFaultCounts faults(uint32_t short_line, uint32_t long_line, uint32_t missing, uint32_t extra, uint32_t few,
                          uint32_t many) {
  return {short_line, long_line, missing, extra, few, many};
}
constexpr sm::SeqFaultCounts kNone{};

// The sequencer's result on `in`: `n` frames, the first one's rows `first`, the fault
// counts `f`.
sm::SeqResult expect_frames(const std::vector<sm::SeqInput>& in, size_t n, const Rows& first,
                            const sm::SeqFaultCounts& f) {
  sm::SeqResult r = sm::seq_frames(in);
  REQUIRE(r.frames.size() == n);
  CHECK(rows(r.frames[0]) == first);
  CHECK(r.faults == f);
  return r;
}

// Records the sink calls as text.
struct Log : sm::SeqSink {
  std::vector<std::string> ev;
  void frame_start(int w, int h) override { ev.push_back(fmt::format("start {}x{}", w, h)); }
  void beat(int x, int y, uint16_t data, bool pad) override {
    ev.push_back(pad ? fmt::format("({},{}) pad", x, y) : fmt::format("({},{}) {}", x, y, data));
  }
  void frame_end(bool faulty) override { ev.push_back(faulty ? "end faulty" : "end"); }
  void fault(sm::SeqFault f) override { ev.emplace_back(sm::seq_fault_name(f)); }
};

}  // namespace

TEST_CASE("seq: fault classes in the ERR_FLAGS bit order of the register map", "[seq]") {
  namespace rm = sm::regmap;
  const std::vector<std::pair<sm::SeqFault, int>> bits = {{sm::SeqFault::kShortLine, rm::kERR_FLAGS_SHORT_LINE_LSB},
                                                          {sm::SeqFault::kLongLine, rm::kERR_FLAGS_LONG_LINE_LSB},
                                                          {sm::SeqFault::kMissingSof, rm::kERR_FLAGS_MISSING_SOF_LSB},
                                                          {sm::SeqFault::kExtraSof, rm::kERR_FLAGS_EXTRA_SOF_LSB},
                                                          {sm::SeqFault::kFewLines, rm::kERR_FLAGS_FEW_LINES_LSB},
                                                          {sm::SeqFault::kManyLines, rm::kERR_FLAGS_MANY_LINES_LSB}};
  REQUIRE(bits.size() == static_cast<size_t>(sm::kNumSeqFaults));
  for (const auto& [f, lsb] : bits) {
    CHECK(sm::seq_fault_bit(f) == static_cast<size_t>(lsb));
    bool named = false;
    for (const auto& field : rm::fields())
      if (std::string(field.name) == std::string("ERR_FLAGS.") + sm::seq_fault_name(f)) named = field.lsb == lsb;
    CHECK(named);
  }
}

TEST_CASE("seq: a clean frame", "[seq]") {
  Stream s;
  s.line({0xa001, 0xa102, 0xa203, 0xa304}, true).line({5, 6, 7, 8}).line({9, 10, 11, 12});
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 1);
  const sm::SeqFrame& f = r.frames[0];
  CHECK(f.w == 4);
  CHECK(f.h == 3);
  CHECK(rows(f) == Rows{{0xa001, 0xa102, 0xa203, 0xa304}, {5, 6, 7, 8}, {9, 10, 11, 12}});
  CHECK(f.left.at(1, 0) == 0x02);  // tdata = {right, left}
  CHECK(f.right.at(1, 0) == 0xa1);
  CHECK(f.complete());
  CHECK(f.beats == 12);
  CHECK_FALSE(f.faulty);
  CHECK(r.faults == kNone);
}

TEST_CASE("seq: a short line is padded with 0", "[seq]") {
  Stream s;
  s.line({1, 2, 3, 4}, true).line({5, 6}).line({9, 10, 11, 12});
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 1);
  CHECK(rows(r.frames[0]) == Rows{{1, 2, 3, 4}, {5, 6, 0, 0}, {9, 10, 11, 12}});
  CHECK(r.frames[0].complete());
  CHECK(r.frames[0].faulty);
  CHECK(r.faults == faults(1, 0, 0, 0, 0, 0));

  SECTION("a one-pixel line, and a short last line ends the frame") {
    Stream t;
    t.line({1}, true).line({5, 6, 7, 8}).line({9, 10});
    const sm::SeqResult q = sm::seq_frames(t.frame(20).in);
    REQUIRE(q.frames.size() == 2);
    CHECK(rows(q.frames[0]) == Rows{{1, 0, 0, 0}, {5, 6, 7, 8}, {9, 10, 0, 0}});
    CHECK(q.frames[0].complete());
    CHECK(rows(q.frames[1]) == Rows{{20, 21, 22, 23}, {24, 25, 26, 27}, {28, 29, 30, 31}});
    CHECK_FALSE(q.frames[1].faulty);
    CHECK(q.faults == faults(2, 0, 0, 0, 0, 0));
  }
}

TEST_CASE("seq: the rest of a long line is dropped", "[seq]") {
  Stream s;
  s.line({1, 2, 3, 4, 50, 51}, true).line({5, 6, 7, 8}).line({9, 10, 11, 12});
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 1);
  CHECK(rows(r.frames[0]) == kFrame1);
  CHECK(r.frames[0].faulty);
  CHECK(r.faults == faults(0, 1, 0, 0, 0, 0));

  SECTION("on the last line: the frame is complete, the drop runs to its tlast") {
    Stream t;
    t.frame(1);
    t.in.back().px.last = false;
    t.line({60, 61});  // the rest of the long line, tlast at its end
    const sm::SeqResult q = sm::seq_frames(t.frame(20).in);
    REQUIRE(q.frames.size() == 2);
    CHECK(rows(q.frames[0]) == kFrame1);
    CHECK(q.frames[0].faulty);
    CHECK_FALSE(q.frames[1].faulty);
    CHECK(q.faults == faults(0, 1, 0, 0, 0, 0));  // not MANY_LINES: the drop took them
  }
  SECTION("a tuser ends the drop and starts a frame: the open one was short of lines") {
    Stream t;
    t.line({1, 2, 3, 4}, true).line({5, 6, 7, 8, 70, 71}, false, false);
    const sm::SeqResult q =
        expect_frames(t.frame(20).in, 2, Rows{{1, 2, 3, 4}, {5, 6, 7, 8}, {0, 0, 0, 0}}, faults(0, 1, 0, 0, 1, 0));
    CHECK(rows(q.frames[1]) == Rows{{20, 21, 22, 23}, {24, 25, 26, 27}, {28, 29, 30, 31}});
  }
}

TEST_CASE("seq: pixels without a frame after reset are a missing sof", "[seq]") {
  Stream s;
  s.line({90, 91, 92, 93}).line({94, 95, 96, 97}).frame(1);
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 1);
  CHECK(rows(r.frames[0]) == kFrame1);
  CHECK_FALSE(r.frames[0].faulty);
  CHECK(r.faults == faults(0, 0, 1, 0, 0, 0));  // one event, not one per pixel or line
}

TEST_CASE("seq: a tuser inside a line completes the frame with 0", "[seq]") {
  Stream s;
  s.line({1, 2, 3, 4}, true).line({5, 6}, false, false).frame(20);
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 2);
  CHECK(rows(r.frames[0]) == Rows{{1, 2, 3, 4}, {5, 6, 0, 0}, {0, 0, 0, 0}});
  CHECK(r.frames[0].complete());
  CHECK(r.frames[0].faulty);
  CHECK(rows(r.frames[1]) == Rows{{20, 21, 22, 23}, {24, 25, 26, 27}, {28, 29, 30, 31}});
  CHECK_FALSE(r.frames[1].faulty);
  CHECK(r.faults == faults(0, 0, 0, 1, 0, 0));

  SECTION("the camera restarts the frame after one pixel") {
    Stream t;
    t.line({1}, true, false).frame(20);
    expect_frames(t.in, 2, Rows{{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}}, faults(0, 0, 0, 1, 0, 0));
  }
}

TEST_CASE("seq: a tuser at a line start before H lines: too few lines", "[seq]") {
  Stream s;
  s.line({1, 2, 3, 4}, true).line({5, 6, 7, 8}).frame(20);
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 2);
  CHECK(rows(r.frames[0]) == Rows{{1, 2, 3, 4}, {5, 6, 7, 8}, {0, 0, 0, 0}});
  CHECK(r.frames[0].faulty);
  CHECK(rows(r.frames[1]) == Rows{{20, 21, 22, 23}, {24, 25, 26, 27}, {28, 29, 30, 31}});
  CHECK(r.faults == faults(0, 0, 0, 0, 1, 0));

  SECTION("a short line then the early tuser: both reported") {
    Stream t;
    t.line({1, 2, 3, 4}, true).line({5}).frame(20);
    expect_frames(t.in, 2, Rows{{1, 2, 3, 4}, {5, 0, 0, 0}, {0, 0, 0, 0}}, faults(1, 0, 0, 0, 1, 0));
  }
}

TEST_CASE("seq: lines after a complete frame: too many lines", "[seq]") {
  Stream s;
  s.frame(1).line({80, 81, 82, 83}).line({84, 85, 86, 87}).frame(20);
  const sm::SeqResult r = sm::seq_frames(s.in);
  REQUIRE(r.frames.size() == 2);
  CHECK(rows(r.frames[0]) == kFrame1);
  CHECK_FALSE(r.frames[0].faulty);  // the frame itself was whole
  CHECK(rows(r.frames[1]) == Rows{{20, 21, 22, 23}, {24, 25, 26, 27}, {28, 29, 30, 31}});
  CHECK(r.faults == faults(0, 0, 0, 0, 0, 1));  // one event for both lines
}

TEST_CASE("seq: host values and enable", "[seq]") {
  SECTION("a disabled frame is dropped silently, up to the next tuser") {
    Stream s;
    s.host.enable = false;
    s.frame(1).line({80, 81});
    s.host.enable = true;
    const sm::SeqResult r = sm::seq_frames(s.frame(20).in);
    REQUIRE(r.frames.size() == 1);
    CHECK(rows(r.frames[0]) == Rows{{20, 21, 22, 23}, {24, 25, 26, 27}, {28, 29, 30, 31}});
    CHECK(r.faults == kNone);
  }
  SECTION("the size is latched at the frame start") {
    Stream s;
    s.host = {2, 2, true};
    s.line({1, 2}, true);
    s.host = {4, 3, true};  // the open frame keeps 2 x 2
    s.line({3, 4}).frame(20);
    const sm::SeqResult r = sm::seq_frames(s.in);
    REQUIRE(r.frames.size() == 2);
    CHECK(r.frames[0].w == 2);
    CHECK(r.frames[0].h == 2);
    CHECK(rows(r.frames[0]) == Rows{{1, 2}, {3, 4}});
    CHECK(r.frames[1].w == 4);
    CHECK(r.faults == kNone);
  }
  SECTION("a frame start with a size of 0 is refused") {
    Stream s;
    s.host = {0, 3, true};
    CHECK_THROWS_AS(sm::seq_frames(s.frame(1).in), std::invalid_argument);
  }
  SECTION("an incomplete frame at the end of the stream stays open") {
    Stream s;
    s.line({1, 2, 3, 4}, true).line({5, 6, 7}, false, false);
    const sm::SeqResult r = sm::seq_frames(s.in);
    REQUIRE(r.frames.size() == 1);
    CHECK_FALSE(r.frames[0].complete());
    CHECK(r.frames[0].beats == 7);
    CHECK(r.faults == kNone);  // no tlast yet on the second line
  }
}

TEST_CASE("seq: the incremental interface", "[seq]") {
  Log log;
  sm::Sequencer seq(log);
  const sm::SeqHost host{4, 2, true};
  Stream s;
  s.host = host;
  s.line({1, 2, 3, 4}, true).line({5, 6});
  for (const auto& i : s.in) seq.push(i.px, i.host);
  CHECK_FALSE(seq.frame_open());
  CHECK(log.ev == std::vector<std::string>{"start 4x2", "(0,0) 1", "(1,0) 2", "(2,0) 3", "(3,0) 4", "(0,1) 5",
                                           "SHORT_LINE", "(1,1) 6", "(2,1) pad", "(3,1) pad", "end faulty"});
  log.ev.clear();
  seq.push({7, false, false}, host);
  CHECK(log.ev == std::vector<std::string>{"MANY_LINES"});

  SECTION("reset abandons the open frame and the history") {
    log.ev.clear();
    seq.push({10, true, false}, host);
    CHECK(seq.frame_open());
    seq.reset();
    CHECK_FALSE(seq.frame_open());
    seq.push({11, false, true}, host);  // no frame completed since the reset
    seq.push({12, true, false}, host);
    CHECK(log.ev == std::vector<std::string>{"start 4x2", "(0,0) 10", "MISSING_SOF", "start 4x2", "(0,0) 12"});
  }
  SECTION("an early tuser: the fault, the padding, the frame's end, then the new frame") {
    log.ev.clear();
    seq.push({10, true, false}, {2, 2, true});
    seq.push({11, false, true}, host);
    seq.push({12, true, false}, {1, 1, true});  // a 1 x 1 frame: its one pixel ends it
    CHECK(log.ev == std::vector<std::string>{"start 2x2", "(0,0) 10", "(1,0) 11", "FEW_LINES", "(0,1) pad", "(1,1) pad",
                                             "end faulty", "start 1x1", "LONG_LINE", "(0,0) 12", "end faulty"});
  }
}
