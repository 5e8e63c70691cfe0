// Unit tests of the generated register map (sm_regmap.hpp from rtl/regmap.json) against
// independent truth: the paper's defaults written out by hand (sm::Regs::defaults, whose
// value registers are generated from the same json), the spec's grid size (sm::RectGrid),
// field widths from docs/algorithm.md and hand-computed addresses.
#include <catch2/catch.hpp>

#include <array>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "configs.hpp"
#include "sm_cmd.hpp"
#include "sm_regmap.hpp"
#include "sm_types.hpp"

namespace rm = sm::regmap;

namespace {
const rm::Field& field(const std::string& name) {
  for (const auto& f : rm::fields())
    if (name == f.name) return f;
  FAIL("no field " << name);
  throw 0;
}
int64_t reset(const std::string& name, const sm::HwConfig& hw) { return field(name).reset.eval(hw); }
}  // namespace

TEST_CASE("reset values are the model's defaults", "[regmap]") {
  for (const auto& [w, h, rows] : {std::tuple{320, 240, 0}, std::tuple{64, 48, 0}, std::tuple{320, 240, 32}}) {
    sm::HwConfig hw;
    hw.max_width = w;
    hw.max_height = h;
    hw.speckle_rows = rows;
    const sm::Regs d = sm::Regs::defaults(hw);
    // every value register: its reset is the default of the sm::Regs member of its name
#define SM_X(NAME, member) CHECK(reset(#NAME ".VALUE", hw) == static_cast<int64_t>(d.member));
    SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
    uint64_t sw = 0;
    for (int k = 0; k < 32; ++k) sw |= static_cast<uint64_t>(d.sw_table[k]) << (2 * k);
    CHECK(static_cast<uint64_t>(reset("SW_TABLE0.CODES", hw)) == (sw & 0xffffffffu));
    CHECK(static_cast<uint64_t>(reset("SW_TABLE1.CODES", hw)) == (sw >> 32));
  }
}

TEST_CASE("the defaults are the paper's (independent of the generated code)", "[regmap]") {
  // sm::Regs' value registers are generated from rtl/regmap.json (sm::RegValues): the
  // numbers of docs/algorithm.md and docs/evaluation.md, written out here once more.
  sm::HwConfig hw;
  hw.max_width = 64;
  hw.max_height = 48;
  const sm::Regs d = sm::Regs::defaults(hw);
  CHECK(d.width == 64);
  CHECK(d.height == 48);
  CHECK(d.gain_l == 256);
  CHECK(d.gain_r == 256);
  CHECK(d.offset_l == 0);
  CHECK(d.offset_r == 0);
  CHECK(d.rect_enable);
  CHECK(d.occ == 11);
  CHECK(d.occ_edge == 7);
  CHECK(d.edge_t == 16);
  CHECK(d.filter_enable == 15);
  CHECK(d.obj_near == 32);
  CHECK(d.obj_tol == 2);
  CHECK(d.obj_min_pixels == 64);
  const std::array<uint8_t, 8> codes{3, 3, 2, 2, 1, 1, 1, 1};
  for (size_t k = 0; k < 32; ++k) CHECK(d.sw_table[k] == (k < 8 ? codes[k] : 0));
  CHECK(d.grid_l.gw == sm::RectGrid::points_w(64));
  CHECK(d.grid_r.gh == sm::RectGrid::points_h(48));
  // a default-constructed Regs holds the same values at HwConfig{} (no grids, no weights)
  const sm::Regs z;
  const sm::Regs zd = sm::Regs::defaults(sm::HwConfig{});
#define SM_X(NAME, member) CHECK(z.member == zd.member);
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  CHECK(z.width == 320);
  CHECK(z.height == 240);
  CHECK(z.grid_l.gw == 0);
  // the member types of today
  static_assert(std::is_same_v<decltype(d.width), int> && std::is_same_v<decltype(d.height), int>);
  static_assert(std::is_same_v<decltype(d.gain_l), uint16_t> && std::is_same_v<decltype(d.offset_l), int16_t>);
  static_assert(std::is_same_v<decltype(d.rect_enable), bool> && std::is_same_v<decltype(d.occ), uint8_t>);
  static_assert(std::is_same_v<decltype(d.filter_enable), uint8_t>);
  static_assert(std::is_same_v<decltype(d.obj_min_pixels), uint16_t>);
}

TEST_CASE("the checked rules reset by configuration (independent of the generated code)", "[regmap]") {
  // Where the speckle stage is built (the zynq configuration) it resets into its speckle
  // mode, elsewhere the per-pixel left-right and agreement rules are on (docs/evaluation.md,
  // "Speckles"); set_config_resets gives a tool's changed configuration the same values.
  const sm::HwConfig paper = sm::named_config("paper"), zynq = sm::named_config("zynq");
  const sm::Regs p = sm::Regs::defaults(paper), z = sm::Regs::defaults(zynq);
  CHECK(!p.speckle_en);
  CHECK(p.lr_en);
  CHECK(p.agree_en);
  CHECK(z.speckle_en);
  CHECK(!z.lr_en);
  CHECK(!z.agree_en);
  sm::Regs moved = p;
  sm::set_config_resets(zynq, moved);
#define SM_X(NAME, member) CHECK(moved.member == z.member);
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  sm::set_config_resets(paper, moved);
#define SM_X(NAME, member) CHECK(moved.member == p.member);
  SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
}

TEST_CASE("the named configurations are the build's (independent of the generated code)", "[regmap]") {
  // CMakeLists.txt's SM_*_PARAMS, written out here once more; the others stay HwConfig{}'s.
  // zynq's and vga's PU is the configure-time choice -DSM_ZYNQ_PU (8 unless changed).
  auto check = [](const std::string& name, std::map<std::string, int> want) {
    INFO(name);
    const sm::HwConfig hw = sm::named_config(name);
    CHECK_NOTHROW(hw.validate());
    for (const auto& [param, value] : sm::HwConfig{}.parameters())
      if (!want.count(param)) want[param] = value;
    CHECK(hw.parameters() == want);
  };
  const std::map<std::string, int> paper{{"MAX_WIDTH", 320}, {"MAX_HEIGHT", 240}, {"DISP", 128},
                                         {"CENSUS", 15},     {"SW", 5},           {"RECT_RADIUS", 18}};
  std::map<std::string, int> zynq = paper, vga = paper;
  zynq.insert({{"PU", SM_ZYNQ_PU}, {"SPECKLE_ROWS", 32}, {"SPECKLE_LABELS", 1024}});
  vga.insert({{"PU", SM_ZYNQ_PU}});
  vga["MAX_WIDTH"] = 640;
  vga["MAX_HEIGHT"] = 480;
  const std::map<std::string, int> small{{"MAX_WIDTH", 64}, {"MAX_HEIGHT", 48}, {"DISP", 16},
                                         {"CENSUS", 7},     {"SW", 3},          {"RECT_RADIUS", 4}};
  std::map<std::string, int> small_fold = small;
  small_fold["PU"] = 4;
  check("paper", paper);
  check("zynq", zynq);
  check("vga", vga);
  check("small", small);
  check("small_fold", small_fold);
  CHECK(sm::config_names() == std::vector<std::string>{"paper", "zynq", "vga", "small", "small_fold"});
  CHECK_THROWS_AS(sm::named_config("zynq7020"), std::invalid_argument);
}

TEST_CASE("every value register's member holds the register's range", "[regmap]") {
  for (const auto& [w, h] : {std::pair{320, 240}, std::pair{640, 480}}) {
    sm::HwConfig hw;
    hw.max_width = w;
    hw.max_height = h;
    const sm::Regs d = sm::Regs::defaults(hw);
    auto holds = [&](const std::string& name, auto member) {
      using T = decltype(member);
      const rm::Field& f = field(name);
      const int64_t lo = f.clamped ? f.min.eval(hw) : (f.is_signed ? -(int64_t{1} << (f.width - 1)) : 0);
      const int64_t hi =
          f.clamped ? f.max.eval(hw) : (f.is_signed ? (int64_t{1} << (f.width - 1)) - 1 : (int64_t{1} << f.width) - 1);
      INFO(name);
      CHECK(static_cast<int64_t>(std::numeric_limits<T>::min()) <= lo);
      CHECK(static_cast<int64_t>(std::numeric_limits<T>::max()) >= hi);
    };
#define SM_X(NAME, member) holds(#NAME ".VALUE", d.member);
    SM_REGMAP_VALUE_REGS(SM_X)
#undef SM_X
  }
}

TEST_CASE("field widths and ranges follow the spec", "[regmap]") {
  sm::HwConfig hw;
  CHECK(field("GAIN_L.VALUE").width == 10);  // Q2.8
  CHECK(field("GAIN_L.VALUE").max.eval(hw) == 1023);
  CHECK(field("OFFSET_L.VALUE").width == 9);
  CHECK(field("OFFSET_L.VALUE").is_signed);
  CHECK(field("OFFSET_L.VALUE").min.eval(hw) == -256);
  CHECK(field("OFFSET_L.VALUE").max.eval(hw) == 255);
  CHECK(field("OCC.VALUE").width == 8);
  CHECK(field("FILTER_ENABLE.VALUE").width == 4);  // F1..F3, F0
  // narrowest line the DP's line memories allow: max(16, DISP/2 + 3), 67 at 128 levels
  CHECK(field("WIDTH.VALUE").min.eval(hw) == 67);
  sm::HwConfig small = hw;
  small.disp = 16;
  CHECK(field("WIDTH.VALUE").min.eval(small) == 16);
  CHECK(field("WIDTH.VALUE").max.eval(hw) == 320);
  CHECK(field("HEIGHT.VALUE").max.eval(hw) == 240);
  CHECK(field("ID.VALUE").reset.eval(hw) == 0x534D4331);
  // every pipeline parameter of sm::Regs is shadowed
  for (const char* n :
       {"WIDTH.VALUE", "HEIGHT.VALUE", "GAIN_L.VALUE", "GAIN_R.VALUE", "OFFSET_L.VALUE", "OFFSET_R.VALUE",
        "RECT_ENABLE.VALUE", "OCC.VALUE", "SW_TABLE0.CODES", "SW_TABLE1.CODES", "FILTER_ENABLE.VALUE", "OBJ_NEAR.VALUE",
        "OBJ_TOL.VALUE", "OBJ_MIN_PIXELS.VALUE", "CONTROL.GRID_BANK"})
    CHECK(field(n).shadow);
}

TEST_CASE("addresses are unique, aligned and below the windows", "[regmap]") {
  std::set<uint32_t> seen;
  for (const auto& r : rm::registers()) {
    CHECK(r.addr % 4 == 0);
    CHECK(r.addr < rm::kObjBase);
    CHECK(seen.insert(r.addr).second);
    uint32_t used = 0;
    for (int i = 0; i < r.num_fields; ++i) {
      const auto& f = rm::fields()[r.first_field + i];
      CHECK((used & f.mask()) == 0);
      used |= f.mask();
    }
  }
  CHECK(rm::kObjBase + rm::kObjSize <= rm::kGridBase);
  CHECK(rm::kGridBase + rm::kGridSize == (1u << rm::kAddrBits));
}

TEST_CASE("window address helpers (hand-computed)", "[regmap]") {
  CHECK(rm::obj_header_addr() == 0x800);
  CHECK(rm::obj_addr(0, 0) == 0x810);
  CHECK(rm::obj_addr(2, 3) == 0x83C);
  CHECK(rm::grid_addr(0, 0, 0) == 0x8000);
  CHECK(rm::grid_addr(0, 1, 0) == 0xA000);
  CHECK(rm::grid_addr(1, 0, 5) == 0xC014);
  CHECK(rm::grid_word(-32, 64) == 0x0040FFE0u);
}

TEST_CASE("the grid window holds the spec's grid", "[regmap]") {
  for (const auto& [w, h] : {std::pair{320, 240}, std::pair{64, 48}, std::pair{640, 480}}) {
    sm::HwConfig hw;
    hw.max_width = w;
    hw.max_height = h;
    const int spec = sm::RectGrid::points_w(w) * sm::RectGrid::points_h(h);
    CHECK(rm::grid_points(hw) == spec);
    CHECK(spec <= (1 << rm::kGridPointBits));
  }
  // MAX_OBJECTS up to the model's limit fits the object window
  CHECK(4 * (rm::kObjFirstIdx + rm::kObjWords * 64) <= rm::kObjSize);
}

TEST_CASE("HwConfig defaults are sm_top's parameter defaults", "[regmap]") {
  // sim/sm_vconfig.hpp relies on this for every parameter a build does not override.
  const std::string text = sm::test::slurp(SM_RTL_DIR "/sm_top.v");
  REQUIRE(!text.empty());
  const std::regex re(R"(parameter\s+([A-Z_]+)\s*=\s*([0-9]+))");
  std::map<std::string, int> p;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    p[(*it)[1].str()] = std::stoi((*it)[2].str());
  // every HwConfig field is a parameter of sm_top with the same default, and back
  CHECK(p == sm::HwConfig{}.parameters());
}

TEST_CASE("verilated_config reads every sm_top parameter a build may override", "[regmap]") {
  // sim/sm_vconfig.hpp is a list by hand: a parameter missing there would give the
  // harness the default while the Verilated RTL has the override.
  const std::string text = sm::test::slurp(SM_RTL_DIR "/../sim/sm_vconfig.hpp");
  REQUIRE(!text.empty());
  for (const auto& [name, value] : sm::HwConfig{}.parameters()) {
    INFO(name);
    CHECK(text.find("#ifdef SM_P_" + name + "\n") != std::string::npos);
    CHECK(text.find(" = SM_P_" + name + ";") != std::string::npos);
  }
}

TEST_CASE("FLUSH_ROWS stays below the 4-frame parameter history", "[regmap]") {
  // sm_top's FLUSH_ROWS (its g_bad_flush check) as HwConfig::flush_rows(); validate()
  // rejects the combinations sm_top rejects.
  const std::string text = sm::test::slurp(SM_RTL_DIR "/sm_top.v");
  REQUIRE(!text.empty());
  CHECK(text.find("localparam BASE_FLUSH_ROWS = (RECT_RADIUS + 1) + (CENSUS - 1) / 2 + (SW - 1) / 2 + 2 + BAND_K + 5 + "
                  "2 +\n"
                  "                               (DISP / 2 + 64 + 1 + 7 + 17 + 15) / 16 + 1;") != std::string::npos);
  CHECK(
      text.find("localparam FLUSH_ROWS = BASE_FLUSH_ROWS + ((SPECKLE_ROWS > 0) ? SPECKLE_ROWS + (`SM_SPECKLE_SLACK + 1 "
                "+ 15) / 16 : 0);") != std::string::npos);
  CHECK(text.find("localparam MIN_HEIGHT = (FLUSH_ROWS / 4 + 1 > 16) ? FLUSH_ROWS / 4 + 1 : 16;") != std::string::npos);
  CHECK(text.find("`SM_BAD_PARAM(g_bad_flush, BASE_FLUSH_ROWS >= 64,") != std::string::npos);
  CHECK(text.find("`SM_BAD_PARAM(g_bad_min_height, MIN_HEIGHT > MAX_HEIGHT,") != std::string::npos);
  sm::HwConfig hw;
  CHECK(hw.flush_rows() == 56);  // paper configuration: 8 rows of margin
  CHECK_NOTHROW(hw.validate());
  hw.census = 15;
  hw.sw = 7;
  hw.disp = 254;
  hw.max_width = 320;
  hw.rect_radius = 20;
  CHECK(hw.flush_rows() == 63);
  CHECK_NOTHROW(hw.validate());
  hw.rect_radius = 21;
  CHECK_THROWS_AS(hw.validate(), std::invalid_argument);
  hw.rect_radius = 18;
  hw.band_k = 16;  // 69 rows
  CHECK_THROWS_AS(hw.validate(), std::invalid_argument);
  // The speckle stage's rows (and two for its queue) lengthen the pipeline; the shortest
  // frame grows instead, so four frames still outlast it.
  sm::HwConfig zynq = sm::named_config("zynq");
  CHECK(zynq.base_flush_rows() == 56);
  CHECK(zynq.flush_rows() == 90);
  CHECK(zynq.min_height() == 23);
  CHECK(4 * zynq.min_height() > zynq.flush_rows());
  CHECK(sm::HwConfig{}.min_height() == 16);
  CHECK_NOTHROW(zynq.validate());
  zynq.max_height = 22;
  CHECK_THROWS_AS(zynq.validate(), std::invalid_argument);
}

TEST_CASE("the object labeller's end-of-frame scan fits a 16x16 frame", "[regmap]") {
  // sm_objects' g_bad_scan: LABEL_SLOTS + MAX_OBJECTS (clog2(DISP) + 1) + 2 <= 256 clocks;
  // validate() rejects what sm_objects rejects, so the model never runs a labeller the RTL
  // cannot build.
  const std::string text = sm::test::slurp(SM_RTL_DIR "/sm_objects.v");
  REQUIRE(!text.empty());
  CHECK(text.find("localparam SCAN_CLKS = LABEL_SLOTS + MAX_OBJECTS * (DW + 1) + 2;") != std::string::npos);
  CHECK(text.find("`SM_BAD_PARAM(g_bad_scan, SCAN_CLKS > 256") != std::string::npos);
  sm::HwConfig hw;  // paper: DISP 128, MAX_OBJECTS 8: 8 * 8 + 2 = 66 clocks besides the labels
  hw.label_slots = 190;
  CHECK_NOTHROW(hw.validate());
  hw.label_slots = 191;
  CHECK_THROWS_AS(hw.validate(), std::invalid_argument);
  hw.disp = 16;  // 8 * 5 + 2 = 42: 214 labels
  hw.label_slots = 214;
  CHECK_NOTHROW(hw.validate());
  hw.label_slots = 215;
  CHECK_THROWS_AS(hw.validate(), std::invalid_argument);
}
