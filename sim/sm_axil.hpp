// AXI4-Lite master for a Verilated top with s_axil_* ports: one transaction at a time,
// driven through the test bench's tick(). Used by the harness and the system tests.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "sm_tb.hpp"

namespace sm {

template <class Top>
class AxilMaster {
 public:
  // step() must advance the design by one clock (it may drive other ports too).
  AxilMaster(Top& top, std::function<void()> step) : top_(top), step_(std::move(step)) { idle(); }
  void idle() {
    top_.s_axil_awvalid = 0;
    top_.s_axil_wvalid = 0;
    top_.s_axil_bready = 0;
    top_.s_axil_arvalid = 0;
    top_.s_axil_rready = 0;
  }
  // Returns the BRESP code (0 OKAY, 2 SLVERR).
  unsigned write(uint32_t addr, uint32_t data, uint8_t strb = 0xf) {
    top_.s_axil_awaddr = addr;
    top_.s_axil_awvalid = 1;
    top_.s_axil_wdata = data;
    top_.s_axil_wstrb = strb;
    top_.s_axil_wvalid = 1;
    top_.s_axil_bready = 1;
    bool aw = false, w = false;
    for (int n = 0; n < kTimeout; ++n) {
      const bool aw_hs = top_.s_axil_awvalid && top_.s_axil_awready;
      const bool w_hs = top_.s_axil_wvalid && top_.s_axil_wready;
      const bool b_hs = top_.s_axil_bvalid && top_.s_axil_bready;
      const unsigned resp = top_.s_axil_bresp;
      step_();
      if (aw_hs) {
        aw = true;
        top_.s_axil_awvalid = 0;
      }
      if (w_hs) {
        w = true;
        top_.s_axil_wvalid = 0;
      }
      if (b_hs) {
        if (!aw || !w) throw std::runtime_error("AXI4-Lite: B before AW and W");
        top_.s_axil_bready = 0;
        return resp;
      }
    }
    throw std::runtime_error(fmt::format("AXI4-Lite write to 0x{:x} timed out", addr));
  }
  // Returns the read data; resp receives RRESP.
  uint32_t read(uint32_t addr, unsigned* resp = nullptr) {
    top_.s_axil_araddr = addr;
    top_.s_axil_arvalid = 1;
    top_.s_axil_rready = 1;
    for (int n = 0; n < kTimeout; ++n) {
      const bool ar_hs = top_.s_axil_arvalid && top_.s_axil_arready;
      const bool r_hs = top_.s_axil_rvalid && top_.s_axil_rready;
      const uint32_t data = top_.s_axil_rdata;
      const unsigned rr = top_.s_axil_rresp;
      step_();
      if (ar_hs) top_.s_axil_arvalid = 0;
      if (r_hs) {
        top_.s_axil_rready = 0;
        if (resp) *resp = rr;
        return data;
      }
    }
    throw std::runtime_error(fmt::format("AXI4-Lite read of 0x{:x} timed out", addr));
  }

 private:
  static constexpr int kTimeout = 1000;
  Top& top_;
  std::function<void()> step_;
};

}  // namespace sm
