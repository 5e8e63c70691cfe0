// Small test-bench wrapper around a Verilated top: tick() evaluates both clock edges,
// dumps the trace when one is open, and advances time. Traces are opt-in; the trace
// format (VCD or FST) is the one the model was Verilated with (--trace / --trace-fst).
// Trace time is in picoseconds (timescale 1 ps): one clock is set_clock_period_ps() long,
// 2 ps unless set (a bench with no real clock), the core clock's real period in stereo_sim.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <verilated.h>
#if VM_TRACE
#include <verilated_vcd_c.h>
#if VM_TRACE_FST
#include <verilated_fst_c.h>
#else
class VerilatedFstC;
#endif
#endif

#ifdef SM_WAVE_FST
class SM_WAVE_FST;
#endif

namespace sm {

// Which signals a trace holds: every traced signal (no scopes), or those in the scopes'
// subtrees (Verilog names with '.', e.g. "TOP.sm_top.u_dp"), each `depth` levels deep (1:
// the scope's own signals, 2: and its children's, ...; 0: every level). Verilator's
// dumpvars(level, hier), the $dumpvars of Verilog.
struct TraceScope {
  struct Scope {
    std::string name;
    int depth = 0;
  };
  std::vector<Scope> scopes;
};

namespace detail {
// The clock input is `clk` on blocks and `aclk` on the AXI top level.
template <class T>
auto clock_of(T& t, int) -> decltype((t.aclk)) {
  return t.aclk;
}
template <class T>
auto clock_of(T& t, long) -> decltype((t.clk)) {
  return t.clk;
}
// The active-low reset: `aresetn` on the AXI top level, `rst_n` on blocks.
template <class T, class = void>
struct has_aresetn : std::false_type {};
template <class T>
struct has_aresetn<T, std::void_t<decltype(std::declval<T&>().aresetn)>> : std::true_type {};
template <class T>
auto& reset_of(T& t) {
  if constexpr (has_aresetn<T>::value)
    return t.aresetn;
  else
    return t.rst_n;
}
#if VM_TRACE
// The trace file class of a model: VerilatedVcdC for --trace, VerilatedFstC for
// --trace-fst. The model's header does not say which: Verilator 5.006 declares trace()
// for its own file class, 5.04x trace(VerilatedTraceBaseC*) for both. So the build names
// its FST model (SM_WAVE_FST, sim/sim.cmake); every other traced model writes VCD.
template <class T>
struct traces_vcd : std::true_type {};
#ifdef SM_WAVE_FST
template <>
struct traces_vcd<::SM_WAVE_FST> : std::false_type {};
#endif
#endif
}  // namespace detail

template <class Top>
class Testbench {
 public:
  Testbench() : ctx_(std::make_unique<VerilatedContext>()) {
    ctx_->randReset(0);
    top_ = std::make_unique<Top>(ctx_.get());
  }
  ~Testbench() {
    close_trace();
    top_->final();
  }
  Testbench(const Testbench&) = delete;
  Testbench& operator=(const Testbench&) = delete;

  Top* operator->() { return top_.get(); }
  Top& top() { return *top_; }
  uint64_t cycles() const { return cycles_; }
  // The clock period in the trace (ps, even: the falling half is half of it; at least 2).
  void set_clock_period_ps(uint64_t ps) { period_ps_ = std::max<uint64_t>(2, ps & ~uint64_t{1}); }
  uint64_t clock_period_ps() const { return period_ps_; }

#if VM_TRACE
  using TraceFile = std::conditional_t<detail::traces_vcd<Top>::value, VerilatedVcdC, VerilatedFstC>;
  static constexpr const char* kTraceFormat = detail::traces_vcd<Top>::value ? "vcd" : "fst";
#else
  static constexpr const char* kTraceFormat = "";
#endif

  // Open a trace file (the model's format) holding the signals `sel` chooses; returns
  // false when the model was built without tracing.
  bool open_trace(const std::string& path, int depth = 99, const TraceScope& sel = {}) {
#if VM_TRACE
    ctx_->traceEverOn(true);
    trace_ = std::make_unique<TraceFile>();
    for (const auto& s : sel.scopes) trace_->dumpvars(s.depth > 0 ? s.depth : 1 << 20, s.name);
    // the time stamps dump() gets are picoseconds, whatever the RTL's `timescale says
    trace_->set_time_unit("1ps");
    trace_->set_time_resolution("1ps");
    top_->trace(trace_.get(), depth);
    trace_->open(path.c_str());
    return trace_->isOpen();
#else
    (void)path;
    (void)depth;
    (void)sel;
    return false;
#endif
  }
  // Open a trace of the signals `sel` chooses at `path` and close it with no value dumped
  // (the clock does not move): the file declares what a trace of `sel` would hold.
  // Verilator 5.006's FST writer crashes on a dump with no signal enabled and writes no
  // readable file without one: a probe should enable a signal that always exists.
  bool probe_trace(const std::string& path, const TraceScope& sel) {
    if (!open_trace(path, 99, sel)) return false;
    // one value dump: a file that Verilator 5.04x's FST writer closes without any is unreadable
    dump(cycles_ * period_ps_);
    close_trace();
    return true;
  }
  void close_trace() {
#if VM_TRACE
    if (trace_) {
      trace_->close();
      trace_.reset();
    }
#endif
  }
  bool tracing() const {
#if VM_TRACE
    return trace_ != nullptr;
#else
    return false;
#endif
  }

  // One clock period: falling half then rising edge.
  void tick() {
    tick([] {});
  }
  // The same with `between_edges` run after the falling half is evaluated: a bench models
  // a synchronous read port there, answering the address the rising edge will register.
  template <class F>
  void tick(F&& between_edges) {
    auto& clk = detail::clock_of(*top_, 0);
    clk = 0;
    top_->eval();
    dump(cycles_ * period_ps_);
    between_edges();
    clk = 1;
    top_->eval();
    dump(cycles_ * period_ps_ + period_ps_ / 2);
    ++cycles_;
  }

 private:
  void dump(uint64_t t) {
#if VM_TRACE
    if (trace_) trace_->dump(t);
#else
    (void)t;
#endif
  }
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Top> top_;
#if VM_TRACE
  std::unique_ptr<TraceFile> trace_;
#endif
  uint64_t cycles_ = 0;
  uint64_t period_ps_ = 2;
};

}  // namespace sm
