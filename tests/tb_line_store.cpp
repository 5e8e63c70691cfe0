// Block test of sm_line_store (the output stage's row store, docs/algorithm.md 9.6): a
// writer stream of rows of width W (random words) and a reader stream of the same rows
// LAG beats later -- anywhere from one row to LINES - 1 rows -- reading a random column of
// its row on every beat; before its first row the reader's beats carry no SOL, as a
// pipeline fresh from reset does. Every word read must be the one written at that row
// and column, and the reader's column r_x must count its own beats. Random ce gaps with
// garbage on the idle clocks.
#include <fmt/format.h>

#include <random>
#include <vector>

#include SM_VTOP_H
#include "sm_block_test.hpp"

using namespace sm::test;

namespace {
constexpr int kLines = SM_P_LINES;
constexpr int kDataW = SM_P_DATA_W;
}  // namespace

int main(int argc, char** argv) {
  const int max_w = SM_P_MAX_WIDTH;
  BlockTest<SM_VTOP> t{"sm_line_store block test"};
  int w = max_w, rows = 12;
  std::vector<int> lags{max_w};
  t.option("--width", w, "row width").range(2, max_w);
  t.option("--rows", rows, "rows written").range(1, 100000);
  t.option("--lags", lags, "reader lags in beats, one run each").delimiter(',').range(1, 1 << 24);
  if (auto rc = t.parse(argc, argv)) return *rc;
  const uint32_t mask = kDataW >= 32 ? 0xffffffffu : (1u << kDataW) - 1;
  std::mt19937 rng(0x5707e + w);
  for (const int lag : lags) {
    if (lag < w || lag > (kLines - 1) * w) {
      fmt::print("tb_line_store: error: lag {} outside {}..{}\n", lag, w, (kLines - 1) * w);
      return 2;
    }
    t.new_model();
    auto& tb = t.tb();
    tb->ce = 1;
    tb->w_sol = 0;
    tb->r_sol = 0;
    t.reset(3);
    t.ce_schedule(11 + lag, 30);
    std::vector<uint32_t> data(static_cast<size_t>(w) * rows);
    for (auto& d : data) d = static_cast<uint32_t>(rng()) & mask;
    const long beats = static_cast<long>(w) * rows;
    long j = 0;  // writer beat; the reader is at j - lag
    while (j < beats + lag) {
      const bool c = t.next_ce();
      const long r = j - lag;
      uint32_t col = 0;
      if (c) {
        tb->w_sol = j % w == 0;  // rows go on after the last one read (virtual rows)
        tb->w_data = j < beats ? data[static_cast<size_t>(j)] : static_cast<uint32_t>(rng()) & mask;
        tb->r_sol = r >= 0 && r % w == 0;
        col = static_cast<uint32_t>(rng() % static_cast<unsigned>(w));
        tb->r_col = col;
        tb->eval();
        if (r >= 0)
          t.check(tb->r_x == static_cast<uint32_t>(r % w),
                  [&] { return fmt::format("lag {} reader beat {}: r_x {} want {}", lag, r, tb->r_x, r % w); });
      } else {
        tb->w_sol = rng() & 1;
        tb->r_sol = rng() & 1;
        tb->w_data = static_cast<uint32_t>(rng()) & mask;
        tb->r_col = static_cast<uint32_t>(rng() % static_cast<unsigned>(w));
      }
      tb.tick();
      if (!c) continue;
      ++j;
      if (r < 0) continue;
      const uint32_t want = data[static_cast<size_t>(r / w * w + col)];
      t.check(tb->r_data == want, [&] {
        return fmt::format("lag {} reader row {} column {}: {:#x} want {:#x}", lag, r / w, col, tb->r_data, want);
      });
    }
  }
  return t.finish(fmt::format("tb_line_store LINES={} MAX_WIDTH={}", kLines, max_w));
}
