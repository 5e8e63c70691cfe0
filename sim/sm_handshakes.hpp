// The stream ports of a Verilated sm_top as one edge will take them: sampled after eval()
// and before the clock edge, so a transfer is counted on the edge that completes it.
#pragma once

#include <cstdint>

namespace sm {

struct Handshakes {
  bool in = false;   // s_axis: the camera's pixel is taken
  bool out = false;  // m_axis: a pixel word leaves
  uint32_t out_data = 0;
  bool out_user = false;  // start of frame
  bool out_last = false;  // end of line
  bool obj = false;       // m_axis_obj: an object-list word leaves
  uint32_t obj_data = 0;
  bool obj_last = false;  // end of the packet

  template <class Top>
  static Handshakes sample(const Top& t) {
    Handshakes h;
    h.in = t.s_axis_tvalid && t.s_axis_tready;
    h.out = t.m_axis_tvalid && t.m_axis_tready;
    h.out_data = t.m_axis_tdata;
    h.out_user = t.m_axis_tuser;
    h.out_last = t.m_axis_tlast;
    h.obj = t.m_axis_obj_tvalid && t.m_axis_obj_tready;
    h.obj_data = t.m_axis_obj_tdata;
    h.obj_last = t.m_axis_obj_tlast;
    return h;
  }
};

}  // namespace sm
