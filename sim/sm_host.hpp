// The host's side of a register schedule: what a host writes over AXI4-Lite, and when,
// so that frame f of a stream is processed with regs[f] (docs/streams.md, "Register
// schedule"). The simulation engine (sm_sim.hpp) runs the plan clock by clock while the
// camera streams.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "post.hpp"
#include "sm_regs_io.hpp"
#include "sm_types.hpp"

namespace sm {

struct HostOp {
  enum Kind {
    kWaitStarted,      // poll STATUS.FRAME_COUNT until n frames of this run have started
    kWaitOutput,       // wait until n frames of this run have left m_axis completely
    kWrite,            // one AXI4-Lite write of `data` to `addr`
    kCheckNotStarted,  // read STATUS: at most n frames may have started (else: late)
  };
  Kind kind;
  uint64_t n = 0;
  uint32_t addr = 0, data = 0;
  int frame = 0;  // the frame whose registers these are
};

// What the plan does for one frame (for the report).
struct FrameHostPlan {
  std::vector<std::string> changed;  // register names written (GRID = the grid window)
  int grid_bank = 0;                 // bank the frame's rectifier reads
  bool grids_written = false;        // its grids went into the inactive bank for it
};

// Frame 0's registers are written before the stream starts (write_registers, bank 0).
// For every later frame f whose registers differ from frame f-1's, the host waits until
// frame f-1 has started (STATUS.FRAME_COUNT; the shadow copy of frame f-1 is then taken),
// writes the changed registers, and reads STATUS once more: frame f must not have
// started yet, else the change was late. Grids: when frame f needs other grids, they go
// into the bank frame f-1 does not use -- unless that bank holds them already -- after
// the last frame that read that bank has left the IP, and CONTROL.GRID_BANK switches
// to it at frame f's start. `late` (a deliberate fault, for tests): the writes wait until
// frame f itself has started, so they reach frame f+1.
inline std::vector<HostOp> plan_register_schedule(const std::vector<Regs>& regs, const HwConfig& hw, bool late,
                                                  std::vector<FrameHostPlan>* plan = nullptr) {
  std::vector<HostOp> ops;
  std::vector<FrameHostPlan> fp(regs.size());
  if (regs.empty()) return ops;
  struct Bank {
    bool loaded = false;
    RectGrid l, r;
    int last_user = -1;  // last frame of this run that reads it
  };
  std::array<Bank, 2> bank;
  bank[0] = {true, regs[0].grid_l, regs[0].grid_r, 0};
  int active = 0;
  for (size_t f = 1; f < regs.size(); ++f) {
    const int fi = static_cast<int>(f);
    const Regs &a = regs[f - 1], &b = regs[f];
    std::vector<HostOp> w;
    const auto wa = register_words(a), wb = register_words(b);
    for (size_t i = 0; i < wb.size(); ++i)
      if (wa[i].value != wb[i].value) {
        w.push_back({HostOp::kWrite, 0, wb[i].addr, wb[i].value, fi});
        fp[f].changed.push_back(wb[i].name);
      }
    if (!same_grid(bank[active].l, b.grid_l) || !same_grid(bank[active].r, b.grid_r)) {
      const int other = 1 - active;
      Bank& o = bank[other];
      if (!o.loaded || !same_grid(o.l, b.grid_l) || !same_grid(o.r, b.grid_r)) {
        if (o.last_user >= 0) w.push_back({HostOp::kWaitOutput, static_cast<uint64_t>(o.last_user) + 1, 0, 0, fi});
        for (int cam = 0; cam < 2; ++cam)
          for (const auto& [addr, word] : grid_words(hw, cam, other, cam ? b.grid_r : b.grid_l))
            w.push_back({HostOp::kWrite, 0, addr, word, fi});
        o = {true, b.grid_l, b.grid_r, -1};
        fp[f].grids_written = true;
        fp[f].changed.push_back("GRID");
      }
      w.push_back({HostOp::kWrite, 0, regmap::kCONTROL, control_word(other), fi});
      fp[f].changed.push_back("CONTROL");
      active = other;
    }
    bank[active].last_user = fi;
    fp[f].grid_bank = active;
    if (w.empty()) continue;
    ops.push_back({HostOp::kWaitStarted, late ? f + 1 : f, 0, 0, fi});
    ops.insert(ops.end(), w.begin(), w.end());
    if (!late) ops.push_back({HostOp::kCheckNotStarted, f, 0, 0, fi});
  }
  if (plan) *plan = std::move(fp);
  return ops;
}

// One packet of m_axis_obj decoded (docs/algorithm.md section 8: a header word
// {0xA5, lost, table_full, too_many, count}, then five words per object).
struct ObjectPacket {
  bool valid = false;  // the header's tag is 0xA5 and the length matches its count
  bool too_many = false, table_full = false, lost = false;
  std::vector<Object> objects;
  std::vector<std::string> notes;  // what each flag dropped and what to change (filled by the report)
};

inline ObjectPacket decode_object_packet(const std::vector<uint32_t>& w) {
  ObjectPacket p;
  if (w.empty()) return p;
  const uint32_t h = w[0];
  const size_t n = h & 0xffu;
  p.lost = (h >> 10) & 1u;
  p.table_full = (h >> 9) & 1u;
  p.too_many = (h >> 8) & 1u;
  p.valid = (h >> 24) == 0xA5u && w.size() == 1 + 5 * n;
  for (size_t i = 0; i < n && 5 + 5 * i < w.size(); ++i) {
    const uint32_t* o = &w[1 + 5 * i];
    Object b;
    b.x0 = static_cast<uint16_t>(o[0] & 0xffffu);
    b.y0 = static_cast<uint16_t>(o[0] >> 16);
    b.x1 = static_cast<uint16_t>(o[1] & 0xffffu);
    b.y1 = static_cast<uint16_t>(o[1] >> 16);
    b.count = o[2];
    b.sum_disp = o[3];
    b.mean_disp = static_cast<uint8_t>(o[4] & 0xffu);
    b.max_disp = static_cast<uint8_t>((o[4] >> 8) & 0xffu);
    p.objects.push_back(b);
  }
  return p;
}

}  // namespace sm
