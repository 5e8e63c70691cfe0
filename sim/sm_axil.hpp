// AXI4-Lite masters for a Verilated top with s_axil_* ports, one transaction at a time:
// AxilMaster blocks (it advances the design itself through step()); AxilAgent does not
// (the caller's clock loop drives it, so a host can talk to the IP while the streams
// run). Used by the harness and the system tests.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "sm_tb.hpp"

namespace sm {

// Non-blocking AXI4-Lite master: start a write or a read, then in every clock call
// sample() after eval() and before the edge, and update() after the edge; update()
// returns true at the edge that completes the transaction (B or R handshake).
template <class Top>
class AxilAgent {
 public:
  explicit AxilAgent(Top& top) : top_(top) {}
  bool busy() const { return state_ != kIdle; }
  // Forgets a transaction in progress (the bus was reset under it).
  void abandon() { state_ = kIdle; }
  void write(uint32_t addr, uint32_t data, uint8_t strb = 0xf) {
    if (busy()) throw std::logic_error("AxilAgent: write while busy");
    top_.s_axil_awaddr = addr;
    top_.s_axil_awvalid = 1;
    top_.s_axil_wdata = data;
    top_.s_axil_wstrb = strb;
    top_.s_axil_wvalid = 1;
    top_.s_axil_bready = 1;
    addr_ = addr;
    aw_ = w_ = false;
    cycles_ = 0;
    state_ = kWrite;
  }
  void read(uint32_t addr) {
    if (busy()) throw std::logic_error("AxilAgent: read while busy");
    top_.s_axil_araddr = addr;
    top_.s_axil_arvalid = 1;
    top_.s_axil_rready = 1;
    addr_ = addr;
    cycles_ = 0;
    state_ = kRead;
  }
  void sample() {
    aw_hs_ = top_.s_axil_awvalid && top_.s_axil_awready;
    w_hs_ = top_.s_axil_wvalid && top_.s_axil_wready;
    b_hs_ = top_.s_axil_bvalid && top_.s_axil_bready;
    ar_hs_ = top_.s_axil_arvalid && top_.s_axil_arready;
    r_hs_ = top_.s_axil_rvalid && top_.s_axil_rready;
    bresp_ = top_.s_axil_bresp;
    rdata_s_ = top_.s_axil_rdata;
    rresp_ = top_.s_axil_rresp;
  }
  bool update() {
    if (state_ == kIdle) return false;
    if (++cycles_ > kTimeout) throw std::runtime_error(fmt::format("AXI4-Lite access to 0x{:x} timed out", addr_));
    if (state_ == kWrite) {
      if (aw_hs_) {
        aw_ = true;
        top_.s_axil_awvalid = 0;
      }
      if (w_hs_) {
        w_ = true;
        top_.s_axil_wvalid = 0;
      }
      if (b_hs_) {
        if (!aw_ || !w_) throw std::runtime_error("AXI4-Lite: B before AW and W");
        top_.s_axil_bready = 0;
        resp_ = bresp_;
        state_ = kIdle;
        return true;
      }
      return false;
    }
    if (ar_hs_) top_.s_axil_arvalid = 0;
    if (r_hs_) {
      top_.s_axil_rready = 0;
      resp_ = rresp_;
      rdata_ = rdata_s_;
      state_ = kIdle;
      return true;
    }
    return false;
  }
  unsigned resp() const { return resp_; }  // BRESP / RRESP of the last transaction
  uint32_t rdata() const { return rdata_; }

 private:
  static constexpr int kTimeout = 1000;
  enum State { kIdle, kWrite, kRead };
  Top& top_;
  State state_ = kIdle;
  uint32_t addr_ = 0;
  bool aw_ = false, w_ = false;
  int cycles_ = 0;
  bool aw_hs_ = false, w_hs_ = false, b_hs_ = false, ar_hs_ = false, r_hs_ = false;
  unsigned bresp_ = 0, rresp_ = 0, resp_ = 0;
  uint32_t rdata_s_ = 0, rdata_ = 0;
};

// Blocking master: one transaction at a time on the non-blocking agent below, the design
// advanced by the caller's step() (sample before the edge, update after it).
template <class Top>
class AxilMaster {
 public:
  // step() must advance the design by one clock (it may drive other ports too).
  AxilMaster(Top& top, std::function<void()> step) : top_(top), agent_(top), step_(std::move(step)) { idle(); }
  void idle() {
    top_.s_axil_awvalid = 0;
    top_.s_axil_wvalid = 0;
    top_.s_axil_bready = 0;
    top_.s_axil_arvalid = 0;
    top_.s_axil_rready = 0;
    agent_.abandon();
  }
  // Returns the BRESP code (0 OKAY, 2 SLVERR).
  unsigned write(uint32_t addr, uint32_t data, uint8_t strb = 0xf) {
    agent_.write(addr, data, strb);
    run();
    return agent_.resp();
  }
  // Returns the read data; resp receives RRESP.
  uint32_t read(uint32_t addr, unsigned* resp = nullptr) {
    agent_.read(addr);
    run();
    if (resp) *resp = agent_.resp();
    return agent_.rdata();
  }

 private:
  void run() {
    do {
      agent_.sample();
      step_();
    } while (!agent_.update());
  }
  Top& top_;
  AxilAgent<Top> agent_;
  std::function<void()> step_;
};

}  // namespace sm
