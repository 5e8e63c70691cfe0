// Small test-bench wrapper around a Verilated top: tick() evaluates both clock edges,
// dumps the trace when one is open, and advances time. Traces are opt-in.
#pragma once

#include <memory>
#include <string>

#include <verilated.h>
#if VM_TRACE
#include <verilated_vcd_c.h>
#endif

namespace sm {

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

  // Open a VCD file; returns false when the model was built without --trace.
  bool open_trace(const std::string& path, int depth = 99) {
#if VM_TRACE
    ctx_->traceEverOn(true);
    trace_ = std::make_unique<VerilatedVcdC>();
    top_->trace(trace_.get(), depth);
    trace_->open(path.c_str());
    return trace_->isOpen();
#else
    (void)path;
    (void)depth;
    return false;
#endif
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
    auto& clk = detail::clock_of(*top_, 0);
    clk = 0;
    top_->eval();
    dump(2 * cycles_);
    clk = 1;
    top_->eval();
    dump(2 * cycles_ + 1);
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
  std::unique_ptr<VerilatedVcdC> trace_;
#endif
  uint64_t cycles_ = 0;
};

}  // namespace sm
