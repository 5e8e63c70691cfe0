// The one kernel of the Verilated block tests (tests/tb_*.cpp, docs/verification.md
// "Block-test kernel"): a bench declares a BlockTest, adds its own knobs to cli(), calls
// parse(), builds its stimulus and expected values, drives the model through tb() with
// reset() and next_ce(), counts every comparison with check() / fail(), and returns
// finish(). The RTL parameters are compile-time SM_P_<NAME> definitions (sm_rtl_test;
// sm::verilated_config() turns them into the model's HwConfig); everything else a bench
// varies is a command-line option, so one binary serves several ctest entries.
#pragma once

#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "beat_schedule.hpp"
#include "sm_bench_options.hpp"
#include "sm_coverage.hpp"
#include "sm_tb.hpp"
#include "sm_vconfig.hpp"  // sm::verilated_config(): the model's HwConfig

namespace sm::test {

// The stream of the frame-streaming benches: `frames` frames of `rows` rows of `width`
// beats back to back, stimulus from `seed`, `idle` percent of the clocks with ce low.
struct StreamShape {
  int width;
  int rows = 6;
  int frames = 3;
  int idle = 30;
  uint32_t seed = 1;
};

template <class Top>
class BlockTest {
 public:
  explicit BlockTest(const std::string& description) : opts_(description) {
    opts_.option("--trace", trace_, "write a trace of the run to this file (model built with TRACE only)");
    opts_.option("--max-report", max_report_, "failures printed in full, the first one always").range(1, 1 << 20);
  }
  BlockTest(const BlockTest&) = delete;
  BlockTest& operator=(const BlockTest&) = delete;

  // The bench's own options go here before parse() (sm_bench_options.hpp).
  template <class T>
  BenchOption option(const std::string& name, T& v, const std::string& help) {
    return opts_.option(name, v, help);
  }
  BenchOption flag(const std::string& name, bool& v, const std::string& help) { return opts_.flag(name, v, help); }
  // The options of a StreamShape; the width's legal range is the block's.
  void stream_options(StreamShape& s, int min_width, int max_width) {
    option("--width", s.width, "active width").range(min_width, max_width);
    option("--rows", s.rows, "rows per frame").range(1, 4096);
    option("--frames", s.frames, "frames back to back").range(1, 64);
    option("--seed", s.seed, "random seed");
    option("--idle", s.idle, "percent of cycles with ce = 0").range(0, 95);
  }

  // Parses the command line and opens the trace if one is asked for. Returns the exit
  // code when the bench must stop here (--help, a bad option), nothing otherwise.
  std::optional<int> parse(int argc, char** argv) {
    if (auto rc = opts_.parse(argc, argv)) return rc;
    if (!trace_.empty() && !tb().open_trace(trace_)) fmt::print("note: model built without tracing, --trace ignored\n");
    return std::nullopt;
  }

  // The model, made on first use, from reset values (Verilator's randReset(0)).
  Testbench<Top>& tb() {
    if (!tb_) {
      tb_ = std::make_unique<Testbench<Top>>();
      cov_ = std::make_unique<CoverageOnExit>(tb_->top().contextp());
    }
    return *tb_;
  }
  Top* operator->() { return tb().operator->(); }
  void tick() { tb().tick(); }
  // Ends the current model (its coverage is written, as a further .dat) so that the next
  // tb() starts a new one: for benches made of independent runs. A model that has not
  // been clocked yet is kept, so a --trace opened by parse() records the first run.
  void new_model() {
    if (tb_ && tb_->cycles() == 0) return;
    cov_.reset();
    tb_.reset();
  }

  // The reset input (rst_n, or aresetn on AXI blocks) low for `cycles` calls of `tick`,
  // then high: for benches whose clock does more than Testbench::tick().
  template <class Tick>
  void reset_by(int cycles, Tick&& tick) {
    sm::detail::reset_of(tb().top()) = 0;
    for (int i = 0; i < cycles; ++i) tick();
    sm::detail::reset_of(tb().top()) = 1;
  }
  // The same with plain ticks; `each` runs before every reset clock, for benches that
  // drive garbage during reset.
  template <class Each>
  void reset(int cycles, Each&& each) {
    reset_by(cycles, [&] {
      each();
      tb().tick();
    });
  }
  void reset(int cycles) {
    reset(cycles, [] {});
  }

  // The clock-enable schedule (CeGen): ce low with probability idle_percent / 100, and
  // for a folded block (min_gap = F) low on the F - 1 clocks after every high one.
  void ce_schedule(uint32_t seed, int idle_percent, int min_gap = 1) {
    ce_ = std::make_unique<CeGen>(seed, idle_percent, min_gap);
  }
  // The next clock's ce, driven on the model's ce input.
  bool next_ce() {
    const bool ce = ce_->next();
    tb()->ce = ce;
    return ce;
  }
  // The schedule's generator, for the benches whose garbage comes from the same stream.
  std::mt19937& ce_rng() { return ce_->rng(); }

  // Output order of a stream stage: the real output beats must come in raster order over
  // frames of width w and these heights.
  void expect_frames(int w, const std::vector<int>& heights) { order_ = std::make_unique<OutputOrder>(w, heights); }
  // (frame, x, y) of a real output beat with this sideband; nothing (and a failure) when
  // the beat is out of order, after which the stream cannot be compared any further.
  std::optional<BeatInfo> next_out(uint8_t side, const std::string& where = "") {
    try {
      return order_->next(side);
    } catch (const std::exception& e) {
      fail(where + e.what());
      return std::nullopt;
    }
  }
  // A failure unless every pixel of the frames came out.
  bool all_out(const std::string& where = "") {
    if (order_->done()) return true;
    fail(where + "not every pixel came out");
    return false;
  }

  // One comparison: counted as passed or failed. `msg` (a string, or a callable returning
  // one, called only on failure so that passing checks cost no formatting) says what was
  // compared and how it differed.
  template <class Msg>
  bool check(bool ok, Msg&& msg) {
    if (ok) {
      ++passed_;
      return true;
    }
    fail(std::forward<Msg>(msg));
    return false;
  }
  void pass() { ++passed_; }
  // A failure without a passing counterpart (a protocol error, a timeout). The first one
  // is the one to debug: it is always printed, then at most --max-report - 1 more.
  template <class Msg>
  void fail(Msg&& msg) {
    ++failed_;
    if (failed_ > max_report_ && !each_kind_) return;
    std::string s;
    if constexpr (std::is_invocable_v<Msg>)
      s = msg();
    else
      s = std::string(std::forward<Msg>(msg));
    const bool fresh = each_kind_ && new_kind(s);
    if (failed_ <= max_report_ || fresh)
      fmt::print("{} {}\n", failed_ == 1 ? "FIRST FAILURE:" : "FAIL:", s);
    else
      ++hidden_;
  }
  // Beyond --max-report, still print the first failure of every kind (its message with
  // the digits taken out): in a long randomised run a flood of one rule must not hide
  // another. For benches whose messages are a fixed set of rules; `first` is the default
  // of --max-report (call before parse()).
  void report_each_kind(long first) {
    each_kind_ = true;
    max_report_ = first;
  }
  long passed() const { return passed_; }
  long failed() const { return failed_; }

  // The summary line "<label>: N passed, M failed<note>" and the exit code: 0 only when
  // nothing failed and something was checked (a bench that compared nothing is broken).
  int finish(const std::string& label, const std::string& note = "") {
    const long hidden = each_kind_ ? hidden_ : failed_ - max_report_;
    if (hidden > 0) fmt::print("({} more failures not shown)\n", hidden);
    fmt::print("{}: {} passed, {} failed{}\n", label, passed_, failed_, note);
    return failed_ == 0 && passed_ > 0 ? 0 : 1;
  }

 private:
  bool new_kind(const std::string& s) {
    std::string kind;
    for (char c : s)
      if (!std::isdigit(static_cast<unsigned char>(c))) kind += c;
    return kinds_.insert(kind).second;
  }

  BenchOptions opts_;
  std::string trace_;
  long max_report_ = 10;
  std::unique_ptr<Testbench<Top>> tb_;
  std::unique_ptr<CoverageOnExit> cov_;  // after tb_: written before the model is deleted
  std::unique_ptr<CeGen> ce_;
  std::unique_ptr<OutputOrder> order_;
  long passed_ = 0, failed_ = 0;
  bool each_kind_ = false;
  std::set<std::string> kinds_;  // of the failures printed, with each_kind_
  long hidden_ = 0;
};

}  // namespace sm::test
