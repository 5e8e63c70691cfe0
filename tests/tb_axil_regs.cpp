// Block test of sm_axil_regs: every register of the generated map (sm_regmap.hpp, from
// rtl/regmap.json) written and read back with walking ones and random values through a
// randomised AXI4-Lite master (AW/W together or apart, delayed BREADY/RREADY), checked
// against a register model built from the same table: clamping, the CLAMPED flag,
// read-only registers, SLVERR on reserved addresses, shadow values changing only at
// frame_start, error flags/counters, the object list read port and grid forwarding.
#include <cstdint>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include SM_VTOP_H
#include "calib_file.hpp"
#include "sm_block_test.hpp"
#include "sm_regmap.hpp"
#include "sm_types.hpp"

namespace rm = sm::regmap;
using Top = SM_VTOP;
using Bench = sm::test::BlockTest<Top>;

namespace {

// The object block's read port as the register file expects it: registered, data of
// obj_rd_idx one clock later.
uint32_t obj_word(uint32_t idx) { return 0x5A000000u ^ (idx * 0x00010203u) ^ (idx << 20); }

// The register file's surroundings on the kernel's model: the object read port, the
// error pulses, the grid and soft-reset outputs, and a randomised AXI4-Lite master.
struct Dut {
  Bench& bench;
  Top* top;
  std::mt19937 rng{12345};
  uint64_t cycle = 0;
  int frame_starts = 0;
  uint8_t err_drive = 0;  // err_pulse for the next clock
  uint8_t err_hold = 0;   // err_pulse on every clock
  int last_bwait = 0;     // clocks the last write's B waited: the clocks after its register update
  std::deque<std::pair<uint32_t, uint32_t>> grid_writes;  // (waddr, wdata)
  int soft_reset_pulses = 0;

  explicit Dut(Bench& b) : bench(b), top(&b.tb().top()) {}
  void tick() {
    top->err_pulse = err_drive | err_hold;
    uint32_t next_obj = 0;
    bench.tb().tick([&] { next_obj = obj_word(top->obj_rd_idx); });
    top->obj_rd_data = next_obj;
    top->frame_start = 0;
    err_drive = 0;
    if (top->grid_we) grid_writes.emplace_back(top->grid_waddr, top->grid_wdata);
    if (top->soft_reset) ++soft_reset_pulses;
    ++cycle;
  }
  void pulse_frame_start() {
    top->frame_start = 1;
    tick();
    ++frame_starts;
  }
  int coin(int percent) { return static_cast<int>(rng() % 100) < percent; }

  // Randomised AXI4-Lite write; returns BRESP.
  unsigned write(uint32_t addr, uint32_t data, uint8_t strb = 0xf) {
    const int mode = static_cast<int>(rng() % 3);  // 0 together, 1 AW first, 2 W first
    const int lag = static_cast<int>(rng() % 4);
    const int bdelay = static_cast<int>(rng() % 4);
    bool aw_done = false, w_done = false;
    int t = 0, bwait = 0;
    top->s_axil_bready = 0;
    for (int n = 0; n < 200; ++n, ++t) {
      top->s_axil_awaddr = addr;
      top->s_axil_wdata = data;
      top->s_axil_wstrb = strb;
      top->s_axil_awvalid = !aw_done && (mode != 2 || t >= lag);
      top->s_axil_wvalid = !w_done && (mode != 1 || t >= lag);
      if (top->s_axil_bvalid) ++bwait;
      top->s_axil_bready = top->s_axil_bvalid && bwait > bdelay;
      top->eval();
      const bool aw_hs = top->s_axil_awvalid && top->s_axil_awready;
      const bool w_hs = top->s_axil_wvalid && top->s_axil_wready;
      const bool b_hs = top->s_axil_bvalid && top->s_axil_bready;
      const unsigned resp = top->s_axil_bresp;
      if (b_hs && !(aw_done && w_done)) bench.check(false, "B before AW and W");
      tick();
      aw_done |= aw_hs;
      w_done |= w_hs;
      if (b_hs) {
        top->s_axil_awvalid = top->s_axil_wvalid = top->s_axil_bready = 0;
        last_bwait = bwait;
        return resp;
      }
    }
    bench.check(false, fmt::format("write 0x{:x} timed out", addr));
    return 3;
  }
  uint32_t read(uint32_t addr, unsigned* resp) {
    const int rdelay = static_cast<int>(rng() % 4);
    bool ar_done = false;
    int rwait = 0;
    for (int n = 0; n < 200; ++n) {
      top->s_axil_araddr = addr;
      top->s_axil_arvalid = !ar_done;
      if (top->s_axil_rvalid) ++rwait;
      top->s_axil_rready = top->s_axil_rvalid && rwait > rdelay;
      top->eval();
      const bool ar_hs = top->s_axil_arvalid && top->s_axil_arready;
      const bool r_hs = top->s_axil_rvalid && top->s_axil_rready;
      const uint32_t d = top->s_axil_rdata;
      *resp = top->s_axil_rresp;
      if (r_hs && !ar_done) bench.check(false, "R before AR");
      tick();
      ar_done |= ar_hs;
      if (r_hs) {
        top->s_axil_arvalid = top->s_axil_rready = 0;
        return d;
      }
    }
    bench.check(false, fmt::format("read 0x{:x} timed out", addr));
    return 0;
  }
};

// Register model: host copy, shadow copy, flags and counters.
struct Model {
  sm::HwConfig hw;
  std::map<uint32_t, uint32_t> host;    // addr -> host-visible word (rw fields only)
  std::map<std::string, int64_t> fval;  // "REG.FIELD" -> host value of rw fields
  std::map<std::string, int64_t> shadow;
  uint8_t flags = 0;
  uint32_t cnt[7] = {};

  explicit Model(const sm::HwConfig& h) : hw(h) {
    for (const auto& f : rm::fields())
      if (f.access == rm::Access::kRW) fval[f.name] = f.reset.eval(hw);
    shadow = fval;
  }
  static const rm::Field* field(const std::string& n) {
    for (const auto& f : rm::fields())
      if (n == f.name) return &f;
    return nullptr;
  }
  // Value a read returns (status fields filled in by the caller's state).
  uint32_t read_value(const rm::Reg& r, int frame_count) const {
    uint32_t v = 0;
    for (int i = 0; i < r.num_fields; ++i) {
      const auto& f = rm::fields()[r.first_field + i];
      const std::string n = f.name;
      uint32_t fv = 0;
      if (f.access == rm::Access::kRW) {
        fv = static_cast<uint32_t>(fval.at(n));
        if (f.is_signed) {  // sign-extended read
          v |= fv;
          continue;
        }
      } else if (f.access == rm::Access::kRO) {
        fv = static_cast<uint32_t>(f.reset.eval(hw));
        if (n == "STATUS.FRAME_COUNT") fv = static_cast<uint32_t>(frame_count & 0xffff);
        if (n == "STATUS.GRID_BANK_ACTIVE") fv = static_cast<uint32_t>(shadow.at("CONTROL.GRID_BANK"));
        if (n.rfind("ERR_CNT", 0) == 0) fv = cnt[flag_bit(n.substr(n.find('.') + 1))];
      } else if (f.access == rm::Access::kW1C) {
        fv = (flags >> f.lsb) & 1u;
      }
      v |= (fv << f.lsb) & f.mask();
    }
    return v;
  }
  static int flag_bit(const std::string& cls) {
    const char* names[8] = {"SHORT_LINE", "LONG_LINE",  "MISSING_SOF",  "EXTRA_SOF",
                            "FEW_LINES",  "MANY_LINES", "OUT_OVERFLOW", "CLAMPED"};
    for (int i = 0; i < 8; ++i)
      if (cls == names[i]) return i;
    throw std::runtime_error("unknown error class " + cls);
  }
  // Apply a write; returns true if the register is writable (OKAY).
  bool write(const rm::Reg& r, uint32_t data, uint8_t strb, int frame_count, bool* pulse_soft) {
    uint32_t smask = 0;
    for (int b = 0; b < 4; ++b)
      if (strb >> b & 1) smask |= 0xffu << (8 * b);
    bool writable = false;
    for (int i = 0; i < r.num_fields; ++i)
      if (rm::fields()[r.first_field + i].access != rm::Access::kRO) writable = true;
    if (!writable) return false;
    const uint32_t merged = (data & smask) | (read_value(r, frame_count) & ~smask);
    const uint32_t ones = data & smask;
    for (int i = 0; i < r.num_fields; ++i) {
      const auto& f = rm::fields()[r.first_field + i];
      const std::string n = f.name;
      if (f.access == rm::Access::kRW) {
        if (f.clamped) {
          const int64_t lo = f.min.eval(hw), hi = f.max.eval(hw);
          int64_t v = f.is_signed ? static_cast<int64_t>(static_cast<int32_t>(merged)) : merged;
          if (v < lo || v > hi) {
            flags |= 0x80;
            v = v < lo ? lo : hi;
          }
          fval[n] = v;
        } else {
          fval[n] = (merged & f.mask()) >> f.lsb;
        }
      } else if (f.access == rm::Access::kW1C) {
        if (ones >> f.lsb & 1) flags &= static_cast<uint8_t>(~(1u << f.lsb));
      } else if (f.access == rm::Access::kWP) {
        if (n == "CONTROL.SOFT_RESET") *pulse_soft = (ones >> f.lsb) & 1;
        if (n == "CONTROL.CLEAR_ERRORS" && ((ones >> f.lsb) & 1)) {
          flags = 0;
          for (auto& c : cnt) c = 0;
        }
      }
    }
    return true;
  }
};

// The model's port cfg_<member> of a value register, when sm_axil_regs has one: a register
// added to regmap.json is stored, clamped, read back and shadowed by the table-driven
// register file at once, but its shadow reaches a port (and the pipeline) only once the
// RTL uses it; until then only its host copy (reads) is checked.
#define SM_X(NAME, member)                                                                 \
  template <class T>                                                                       \
  auto cfg_##member(T& t, int)->decltype((void)t.cfg_##member, std::optional<int64_t>{}) { \
    return static_cast<int64_t>(t.cfg_##member);                                           \
  }                                                                                        \
  template <class T>                                                                       \
  std::optional<int64_t> cfg_##member(T&, long) {                                          \
    return std::nullopt;                                                                   \
  }
SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X

// Shadow ports by field name (nullopt: a value register without its cfg_ port); every
// other shadow field of the map must be listed here.
std::optional<int64_t> shadow_port(Top& t, const std::string& n) {
  auto sx = [](uint32_t v, int bits) {
    return static_cast<int64_t>(static_cast<int32_t>(v << (32 - bits)) >> (32 - bits));
  };
  if (n == "CONTROL.GRID_BANK") return t.cfg_grid_bank;
  if (n == "SW_TABLE0.CODES") return static_cast<uint32_t>(t.cfg_sw_table);
  if (n == "SW_TABLE1.CODES") return static_cast<uint32_t>(t.cfg_sw_table >> 32);
  // every value register: port cfg_<member>, sign-extended where the field is signed
  bool is_signed = false;
  int bits = 32;
  for (const auto& f : rm::fields())
    if (n == f.name) is_signed = f.is_signed, bits = f.width;
#define SM_X(NAME, member)                                          \
  if (n == #NAME ".VALUE") {                                        \
    const std::optional<int64_t> v = cfg_##member(t, 0);            \
    if (v && is_signed) return sx(static_cast<uint32_t>(*v), bits); \
    return v;                                                       \
  }
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  throw std::runtime_error("tb_axil_regs: no shadow port for " + n);
}

int64_t as_signed_field(int64_t v, const rm::Field& f) {
  if (!f.is_signed) return v;
  return static_cast<int32_t>(static_cast<uint32_t>(v));
}

void check_shadows(Dut& d, const Model& m, const std::string& when) {
  for (const auto& f : rm::fields()) {
    if (!f.shadow) continue;
    const int64_t want = as_signed_field(m.shadow.at(f.name), f);
    const std::optional<int64_t> got = shadow_port(*d.top, f.name);
    if (!got) continue;  // no port yet: checked through reads only
    d.bench.check(*got == want, fmt::format("{}: shadow {} expected {} got {}", when, f.name, want, *got));
  }
  d.bench.check(d.top->enable == m.fval.at("CONTROL.ENABLE"), when + ": enable port");
  d.bench.check(d.top->host_width == m.fval.at("WIDTH.VALUE"), when + ": host_width port");
  d.bench.check(d.top->host_height == m.fval.at("HEIGHT.VALUE"), when + ": host_height port");
}

const rm::Reg& reg_at(uint32_t addr) {
  for (const auto& r : rm::registers())
    if (r.addr == addr) return r;
  throw std::runtime_error(fmt::format("no register at 0x{:x}", addr));
}

void read_all(Dut& d, const Model& m, const std::string& when) {
  for (const auto& r : rm::registers()) {
    unsigned resp = 9;
    const uint32_t got = d.read(r.addr, &resp);
    const uint32_t want = m.read_value(r, d.frame_starts);
    d.bench.check(resp == 0, fmt::format("{}: read {} resp {}", when, r.name, resp));
    d.bench.check(got == want, fmt::format("{}: read {} expected 0x{:08x} got 0x{:08x}", when, r.name, want, got));
  }
}

}  // namespace

int main(int argc, char** argv) {
  Bench t{"sm_axil_regs block test"};
  if (auto rc = t.parse(argc, argv)) return *rc;
  const sm::HwConfig hw = sm::verilated_config();
  Dut d{t};
  Model m(hw);
  t.reset_by(4, [&] { d.tick(); });
  d.tick();

  // Every shadow field must be mapped to a port (fails on a new json field other than a
  // value register); a value register without its cfg_ port is named.
  std::string no_port;
  for (const auto& f : rm::fields())
    if (f.shadow && !shadow_port(*d.top, f.name)) no_port += std::string(no_port.empty() ? "" : ", ") + f.name;
  if (!no_port.empty()) fmt::print("tb_axil_regs: no cfg_ port (shadow not observable, reads checked): {}\n", no_port);

  // 1. reset values, cross-checked against the model's defaults
  read_all(d, m, "reset");
  check_shadows(d, m, "reset");
  {
    const sm::Regs def = sm::Regs::defaults(hw);
    bool same = true;
#define SM_X(NAME, member) same = same && m.fval.at(#NAME ".VALUE") == static_cast<int64_t>(def.member);
    SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
    t.check(same, "reset values differ from sm::Regs::defaults");
    uint64_t sw = 0;
    for (int k = 0; k < 32; ++k) sw |= static_cast<uint64_t>(def.sw_table[k]) << (2 * k);
    t.check(static_cast<uint64_t>(d.top->cfg_sw_table) == sw, "SW_TABLE reset differs from defaults");
  }

  // 2. walking ones and random values on every writable register; shadows must not move
  std::mt19937 rng(777);
  for (const auto& r : rm::registers()) {
    std::vector<std::pair<uint32_t, uint8_t>> vals;
    for (int b = 0; b < 32; ++b) vals.emplace_back(1u << b, 0xf);
    for (int i = 0; i < 24; ++i) {
      uint32_t v = rng();
      if (i % 3 == 0) v &= 0x1ff;                                                     // in range of most registers
      if (i % 3 == 1) v = static_cast<uint32_t>(-static_cast<int32_t>(rng() % 400));  // negatives
      vals.emplace_back(v, static_cast<uint8_t>(i < 16 ? 0xf : rng() % 16));
    }
    for (const auto& [v, strb] : vals) {
      if (r.addr == rm::kCONTROL && (v & 2)) continue;  // soft reset is tested below
      bool soft = false;
      const bool ok = m.write(r, v, strb, d.frame_starts, &soft);
      const unsigned resp = d.write(r.addr, v, strb);
      t.check(resp == (ok ? 0u : 2u), fmt::format("write {} = 0x{:x} strb {:x}: resp {}", r.name, v, strb, resp));
      unsigned rresp = 9;
      const uint32_t got = d.read(r.addr, &rresp);
      const uint32_t want = m.read_value(r, d.frame_starts);
      t.check(
          rresp == 0 && got == want,
          fmt::format("{} after writing 0x{:x} strb {:x}: expected 0x{:08x} got 0x{:08x}", r.name, v, strb, want, got));
      // CLAMPED flag as the model says (then clear it with W1C)
      const uint32_t fl = d.read(rm::kERR_FLAGS, &rresp);
      t.check(fl == m.flags,
              fmt::format("ERR_FLAGS after {} = 0x{:x}: expected 0x{:x} got 0x{:x}", r.name, v, m.flags, fl));
      if (m.flags) {
        bool s = false;
        m.write(reg_at(rm::kERR_FLAGS), 0xff, 0xf, d.frame_starts, &s);
        d.write(rm::kERR_FLAGS, 0xff);
      }
    }
    check_shadows(d, m, std::string("after writing ") + r.name);
  }
  // 3. frame_start copies the host values
  d.pulse_frame_start();
  m.shadow = m.fval;
  check_shadows(d, m, "after frame_start");
  {
    bool s = false;
    m.write(reg_at(rm::kWIDTH), 33, 0xf, d.frame_starts, &s);  // WIDTH
    d.write(rm::kWIDTH, 33);
    check_shadows(d, m, "width written, no frame_start");
    d.pulse_frame_start();
    m.shadow = m.fval;
    check_shadows(d, m, "second frame_start");
  }
  read_all(d, m, "after frame starts");

  // 4. reserved addresses, read-only registers, windows
  std::map<uint32_t, bool> known;
  for (const auto& r : rm::registers()) known[r.addr] = true;
  auto expect_err = [&](uint32_t a, bool rd, bool wr) {
    unsigned resp = 0;
    if (rd) {
      d.read(a, &resp);
      t.check(resp == 2, fmt::format("read of 0x{:x}: expected SLVERR, got {}", a, resp));
    }
    if (wr) {
      const size_t before = d.grid_writes.size();
      t.check(d.write(a, rng()) == 2, fmt::format("write of 0x{:x}: expected SLVERR", a));
      t.check(d.grid_writes.size() == before, fmt::format("write of 0x{:x} was forwarded", a));
    }
  };
  for (uint32_t a = 0; a < rm::kObjBase; a += 4)
    if (!known.count(a)) expect_err(a, true, true);
  for (int i = 0; i < 64; ++i) {  // random addresses between the windows, unaligned too
    const uint32_t a = rm::kObjBase + rm::kObjSize + rng() % (rm::kGridBase - rm::kObjBase - rm::kObjSize);
    expect_err(a, true, true);
  }
  read_all(d, m, "after reserved writes");
  check_shadows(d, m, "after reserved writes");

  // 5. object list through the read port
  const uint32_t obj_end = rm::kObjFirstIdx + rm::kObjWords * static_cast<uint32_t>(hw.max_objects);
  for (uint32_t idx = 0; idx < rm::kObjSize / 4; ++idx) {
    const uint32_t a = rm::kObjBase + 4 * idx;
    const bool valid = idx == 0 || (idx >= rm::kObjFirstIdx && idx < obj_end);
    unsigned resp = 9;
    const uint32_t got = d.read(a, &resp);
    if (valid) {
      t.check(resp == 0 && got == obj_word(idx),
              fmt::format("object word {}: expected 0x{:08x} got 0x{:08x} resp {}", idx, obj_word(idx), got, resp));
      t.check(d.write(a, 1) == 2, fmt::format("write to object word {} not SLVERR", idx));
    } else {
      t.check(resp == 2, fmt::format("object index {}: expected SLVERR", idx));
    }
  }
  t.check(rm::obj_addr(1, 2) == rm::kObjBase + 4 * (rm::kObjFirstIdx + rm::kObjWords + 2), "obj_addr()");

  // 6. grid window: forwarded writes, bad points, partial strobes, reads. A point is the
  // rectifier's grid address {gy, gx} with a power-of-two row (model/calib_file.hpp).
  const int gw_pts = sm::RectGrid::points_w(hw.max_width), gh_pts = sm::RectGrid::points_h(hw.max_height);
  const int gwmax = sm::grid_gwmax(hw.max_width), ghmax = sm::grid_ghmax(hw.max_height);
  const int pb = sm::clog2(gwmax * ghmax);
  auto point_of = [&](int gx, int gy) { return gy * gwmax + gx; };
  for (int i = 0; i < 200; ++i) {
    const int cam = static_cast<int>(rng() % 2), bank = static_cast<int>(rng() % 2);
    const int gx = i < 4 ? (i % 2 ? gw_pts - 1 : 0) : static_cast<int>(rng() % gw_pts);
    const int gy = i < 4 ? (i < 2 ? 0 : gh_pts - 1) : static_cast<int>(rng() % gh_pts);
    const int point = point_of(gx, gy);
    const uint32_t data = rng();
    d.grid_writes.clear();
    t.check(d.write(rm::grid_addr(cam, bank, point), data) == 0, "grid write resp");
    const uint32_t want_addr =
        (static_cast<uint32_t>(cam) << (pb + 1)) | (static_cast<uint32_t>(bank) << pb) | static_cast<uint32_t>(point);
    t.check(d.grid_writes.size() == 1 && d.grid_writes[0].first == want_addr && d.grid_writes[0].second == data,
            fmt::format("grid write cam {} bank {} point {}: forwarded {} writes, addr 0x{:x} (want 0x{:x})", cam, bank,
                        point, d.grid_writes.size(), d.grid_writes.empty() ? 0 : d.grid_writes[0].first, want_addr));
  }
  for (int i = 0; i < 20; ++i) {
    // outside the grid: a column past the last point, a row past the last, or above PB bits
    int point;
    if (i % 3 == 0 && gw_pts < gwmax)
      point = point_of(gw_pts + static_cast<int>(rng() % (gwmax - gw_pts)), static_cast<int>(rng() % gh_pts));
    else if (i % 3 == 1 && gh_pts < ghmax)
      point = point_of(static_cast<int>(rng() % gw_pts), gh_pts + static_cast<int>(rng() % (ghmax - gh_pts)));
    else
      point = (1 << pb) + static_cast<int>(rng() % ((1 << rm::kGridPointBits) - (1 << pb)));
    expect_err(rm::grid_addr(static_cast<int>(rng() % 2), static_cast<int>(rng() % 2), point), true, true);
    const uint32_t good =
        rm::grid_addr(0, 1, point_of(static_cast<int>(rng() % gw_pts), static_cast<int>(rng() % gh_pts)));
    expect_err(good, true, false);  // write-only window
    d.grid_writes.clear();
    t.check(d.write(good, 5, 0x7) == 2 && d.grid_writes.empty(), "partial grid write accepted");
  }

  // 7. error pulses: flags, counters, W1C, CLEAR_ERRORS, saturation
  for (int i = 0; i < 300; ++i) {
    const uint8_t e = static_cast<uint8_t>(rng() & 0x7f & rng());
    d.err_drive = e;
    d.tick();
    for (int c = 0; c < 7; ++c)
      if (e >> c & 1) {
        m.flags |= static_cast<uint8_t>(1u << c);
        m.cnt[c] = std::min<uint32_t>(m.cnt[c] + 1, 0xffff);
      }
  }
  read_all(d, m, "after error pulses");
  {
    bool s = false;
    m.write(reg_at(rm::kERR_FLAGS), 0x15, 0xf, d.frame_starts, &s);
    d.write(rm::kERR_FLAGS, 0x15);
    read_all(d, m, "after W1C");
    m.write(reg_at(rm::kCONTROL), 0x8 | 1 | static_cast<uint32_t>(m.fval.at("CONTROL.GRID_BANK") << 2), 0xf,
            d.frame_starts, &s);
    d.write(rm::kCONTROL, 0x8 | 1 | static_cast<uint32_t>(m.fval.at("CONTROL.GRID_BANK") << 2));
    read_all(d, m, "after CLEAR_ERRORS");
  }
  for (int i = 0; i < 70000; ++i) {
    d.err_drive = 0x41;
    d.tick();
  }
  m.flags |= 0x41;
  m.cnt[0] = m.cnt[6] = 0xffff;
  read_all(d, m, "after saturation");
  // An error in the very clock of CLEAR_ERRORS wins over the clear: its flag stays set and
  // its counter restarts at 1. The pulse is held through the whole write, so the counter
  // then reads 1 + the clocks after the register update (the clocks B waited).
  {
    bool s = false;
    const uint32_t v = 0x8 | 1 | static_cast<uint32_t>(m.fval.at("CONTROL.GRID_BANK") << 2);
    m.write(reg_at(rm::kCONTROL), v, 0xf, d.frame_starts, &s);
    d.err_hold = 0x02;
    d.write(rm::kCONTROL, v);
    d.err_hold = 0;
    m.flags |= 0x02;
    m.cnt[1] = 1 + static_cast<uint32_t>(d.last_bwait);
    read_all(d, m, "after CLEAR_ERRORS with an error in the same clock");
  }

  // 8. soft reset: a one-clock pulse, reads 0, registers keep their values
  d.soft_reset_pulses = 0;
  {
    bool soft = false;
    const uint32_t v = 2 | 1 | static_cast<uint32_t>(m.fval.at("CONTROL.GRID_BANK") << 2);
    m.write(reg_at(rm::kCONTROL), v, 0xf, d.frame_starts, &soft);
    d.write(rm::kCONTROL, v);
    for (int i = 0; i < 5; ++i) d.tick();
    t.check(soft && d.soft_reset_pulses == 1, fmt::format("soft reset pulses: {}", d.soft_reset_pulses));
  }
  read_all(d, m, "after soft reset");
  // 9. enable and grid bank flip: enable at once, bank at the next frame
  {
    bool s = false;
    m.write(reg_at(rm::kCONTROL), 4, 0xf, d.frame_starts, &s);
    d.write(rm::kCONTROL, 4);
    check_shadows(d, m, "bank flipped, enable off");
    for (int i = 0; i < 5; ++i) d.pulse_frame_start();
    m.shadow = m.fval;
    check_shadows(d, m, "bank flip applied");
    read_all(d, m, "frame counter");
  }

  return t.finish(fmt::format("tb_axil_regs MAX_WIDTH={} DISP={}", hw.max_width, hw.disp));
}
