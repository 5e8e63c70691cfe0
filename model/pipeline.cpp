#include "pipeline.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "kernels.hpp"
#include "parallel.hpp"
#include "smooth.hpp"
#include "speckle.hpp"

namespace sm {

void validate_regs(const Regs& r, const HwConfig& hw) {
  auto bad = [](const std::string& m) { throw std::invalid_argument(m); };
  if (r.width < hw.min_width() || r.width > hw.max_width)
    bad(fmt::format("width {} outside {}..{}", r.width, hw.min_width(), hw.max_width));
  if (r.height < hw.min_height() || r.height > hw.max_height)
    bad(fmt::format("height {} outside {}..{}", r.height, hw.min_height(), hw.max_height));
  if (r.gain_l > 1023 || r.gain_r > 1023) bad("gain above 1023 (10-bit Q2.8)");
  if (r.offset_l < -256 || r.offset_l > 255 || r.offset_r < -256 || r.offset_r > 255)
    bad("offset outside -256..255 (9-bit signed)");
  for (uint8_t c : r.sw_table)
    if (c > 3) bad("sw_table code above 3");
  for (const RectGrid* g : {&r.grid_l, &r.grid_r})
    if (g->gw != 0 && (g->gw != RectGrid::points_w(r.width) || g->gh != RectGrid::points_h(r.height)))
      bad(fmt::format("rectification grid is {}x{} points, the active size needs {}x{}", g->gw, g->gh,
                      RectGrid::points_w(r.width), RectGrid::points_h(r.height)));
}

namespace {

// What every band of run_pipeline's row stream reads.
struct Rows {
  const Image8 &rl, &rr;
  const HwConfig& hw;
  const Regs& regs;
  detail::CensusPad pl, pr;
  detail::AggRow ag;
};

uint8_t* align64(uint8_t* p) { return p + (64 - reinterpret_cast<uintptr_t>(p) % 64) % 64; }

// Output rows y0..y1-1 of census, cost (r.raw), aggregation (r.agg) and DP (r.dp);
// ms[0..4] += the time of each of the five steps (census, cost, aggregation, trellis, evidence).
void stream_rows(const Rows& s, int y0, int y1, bool keep_volumes, PipelineResult& r, double* ms) {
  using clock = std::chrono::steady_clock;
  const HwConfig& hw = s.hw;
  const Regs& regs = s.regs;
  const int w = regs.width, h = regs.height, nd = hw.disp, ra = (hw.sw - 1) / 2, sw = hw.sw;
  const size_t row = static_cast<size_t>(w) * nd;
  const auto cb = static_cast<uint8_t>(hw.census_bits());
  std::vector<CensusVec> cl(static_cast<size_t>(w)), cr(static_cast<size_t>(w));
  // Speed: the ring and the aggregated line start on a 64-byte boundary (the kernels read a
  // pixel's levels as 64-byte vectors, which then do not straddle cache lines when DISP is
  // a multiple of 64), and the ring's rows are 5 cache lines more than a row apart (a
  // window's rows at x are then not a multiple of 4 KB apart and use different L1 sets:
  // -7% aggregation time against aligned rows, +6% for aligned rows without the gap).
  const size_t ring_row = row + 320;
  std::vector<uint8_t> ring_buf(static_cast<size_t>(sw) * ring_row + detail::kCostPad + 64);
  std::vector<uint8_t> agg_buf(keep_volumes ? 0 : row + 64);
  uint8_t* const ring = align64(ring_buf.data());
  uint8_t* const agg_line = align64(agg_buf.data());
  std::vector<const uint8_t*> win(static_cast<size_t>(sw));
  DpScratch scratch;
  DpLine line;
  std::vector<uint8_t> pen;  // the row's occlusion penalties (edge_penalties)
  auto since = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  for (int y = std::max(0, y0 - ra); y < y1 + ra; ++y) {
    if (y < h) {
      const auto t0 = clock::now();
      detail::census_row(s.pl, y, cl.data());
      detail::census_row(s.pr, y, cr.data());
      const auto t1 = clock::now();
      uint8_t* c = &ring[static_cast<size_t>(y % sw) * ring_row];
      if (keep_volumes && y >= y0 && y < y1) {
        uint8_t* hr = r.raw.pix(0, y);
        detail::cost_row(cl.data(), cr.data(), w, nd, cb, 0, hr);
        detail::add_term_row(s.pl.row(y), s.pr.row(y), w, nd, hw, hw.cost_shift, cb, hr);
        for (size_t i = 0; i < row; ++i) c[i] = static_cast<uint8_t>(hr[i] >> hw.cost_shift);
      } else {
        detail::cost_row(cl.data(), cr.data(), w, nd, cb, hw.cost_shift, c);
        detail::add_term_row(s.pl.row(y), s.pr.row(y), w, nd, hw, 0, cb >> hw.cost_shift, c);
      }
      const auto t2 = clock::now();
      ms[0] += since(t0, t1);
      ms[1] += since(t1, t2);
    }
    const int ya = y - ra;  // the row whose window is complete
    if (ya < y0) continue;
    const auto t0 = clock::now();
    for (int j = -ra; j <= ra; ++j)
      win[static_cast<size_t>(j + ra)] =
          (ya + j >= 0 && ya + j < h) ? &ring[static_cast<size_t>((ya + j) % sw) * ring_row] : nullptr;
    uint8_t* a = keep_volumes ? r.agg.pix(0, ya) : agg_line;
    detail::agg_row(s.ag, win.data(), s.rl.px.data(), ya, a);
    const auto t1 = clock::now();
    edge_penalties(&s.rl.px[static_cast<size_t>(ya) * w], w, regs.occ, regs.occ_edge, regs.edge_t, pen);
    trellis_line_pen(a, w, pen.data(), hw, scratch, line);
    std::copy(line.disp.begin(), line.disp.end(), &r.dp.at(0, ya));
    const auto t3 = clock::now();
    evidence_line(a, w, nd, line, ya, r.evidence);  // writes row ya only: safe across bands
    const auto t2 = clock::now();
    ms[2] += since(t0, t1);
    ms[3] += since(t1, t3);
    ms[4] += since(t3, t2);
  }
}

// The output words (r.out) and the object list (r.objects) of a frame with t >= 2 threads,
// the rows in chunks of kChunk: band 0 labels the chunks in order (the labeller reads the
// words in raster order, so it is serial) and, while the next chunk is not ready, makes a
// chunk's words itself; the other bands make the chunks' words and object levels in
// order. So the labelling overlaps the output words instead of following them. The same
// words (make_output_rows) and the same list (ObjectLabeller, the rows in order) as
// make_output and separate_objects. Returns when the last chunk's words were made.
std::chrono::steady_clock::time_point output_and_objects(PipelineResult& r, const Regs& regs, const HwConfig& hw,
                                                         int t) {
  constexpr int kChunk = 8;
  const int w = r.post.w, h = r.post.h, nd = hw.disp, nc = (h + kChunk - 1) / kChunk;
  const OutputRegs oregs = output_regs(regs);
  r.out = OutImage(w, h);
  DispImage levels(w, h);
  std::unique_ptr<std::atomic<bool>[]> ready(new std::atomic<bool>[static_cast<size_t>(nc)]);
  for (int c = 0; c < nc; ++c) ready[c].store(false, std::memory_order_relaxed);
  std::atomic<int> next{0}, made{0};
  std::chrono::steady_clock::time_point last{};  // (written by the thread that makes the last chunk)
  auto make_one = [&]() {                        // the next chunk nobody has taken; false when none is left
    const int c = next.fetch_add(1);
    if (c >= nc) return false;
    const int y0 = c * kChunk, y1 = std::min(h, y0 + kChunk);
    make_output_rows(r.evidence, r.post, nd, oregs, 0, y0, y1, r.out);
    object_levels_rows(r.out, y0, y1, levels);
    ready[c].store(true, std::memory_order_release);
    if (made.fetch_add(1) + 1 == nc) last = std::chrono::steady_clock::now();
    return true;
  };
  ObjectLabeller lab(w, regs, hw);
  parallel_bands(t, t, [&](int, int, int b) {
    if (b != 0) {
      while (make_one()) {
      }
      return;
    }
    for (int c = 0; c < nc; ++c) {
      while (!ready[c].load(std::memory_order_acquire))
        if (!make_one()) std::this_thread::yield();  // (another band is making it)
      for (int y = c * kChunk; y < std::min(h, (c + 1) * kChunk); ++y) lab.row(&levels.at(0, y), y);
    }
  });
  r.objects = lab.finish();
  return last;
}

}  // namespace

PipelineResult run_pipeline(const Image8& left, const Image8& right, const HwConfig& hw, const Regs& regs,
                            bool keep_volumes, int threads) {
  hw.validate();
  validate_regs(regs, hw);
  if (left.w != regs.width || left.h != regs.height || right.w != regs.width || right.h != regs.height)
    throw std::invalid_argument(fmt::format("images {}x{} / {}x{} do not match the active size {}x{}", left.w, left.h,
                                            right.w, right.h, regs.width, regs.height));
  PipelineResult r;
  using clock = std::chrono::steady_clock;
  auto t = clock::now();
  auto lap = [&](const char* name) {
    auto now = clock::now();
    r.stage_ms.emplace_back(name, std::chrono::duration<double, std::milli>(now - t).count());
    t = now;
  };
  const int w = regs.width, h = regs.height, nd = hw.disp;
  prepare_bands(h, threads);  // (the pool's threads wake up during the allocations below)
  // The frames the row stream writes (below).
  if (keep_volumes) {
    r.raw = CostVolume(w, h, nd);
    r.agg = CostVolume(w, h, nd);
  }
  r.dp = DispImage(w, h);
  r.evidence = Evidence(w, h);
  lap("setup");
  // The two images on two threads when there are threads (image 0 left, 1 right).
  auto each_image = [threads](auto&& f) {
    parallel_bands(2, threads, [&f](int i0, int i1, int) {
      for (int i = i0; i < i1; ++i) f(i == 0);
    });
  };
  each_image([&](bool l) {
    (l ? r.bl : r.br) =
        l ? brightness(left, regs.gain_l, regs.offset_l) : brightness(right, regs.gain_r, regs.offset_r);
  });
  lap("brightness");
  each_image([&](bool l) {
    (l ? r.rl : r.rr) = rectify(l ? r.bl : r.br, l ? regs.grid_l : regs.grid_r, regs.rect_enable, hw);
  });
  lap("rectify");

  // Census, cost, aggregation and DP stream row by row through the row kernels the
  // stage functions use (model/kernels.hpp), so the results are the stage functions'
  // bits: row y's costs enter a ring of SW rows of C = H >> COST_SHIFT, and once the
  // ring holds rows y-2R .. y, row y-R is aggregated and goes through the DP. Only the
  // volumes that are kept are ever allocated whole. With threads > 1 each band of rows
  // streams on its own thread with its own ring (the 2R cost rows around a band edge
  // are computed by both bands; each output row is written by its band only). Each
  // stage's time is summed over its rows and bands (stage_ms keeps the stage order).
  const Rows rows{r.rl,
                  r.rr,
                  hw,
                  regs,
                  {r.rl, (hw.census - 1) / 2},
                  {r.rr, (hw.census - 1) / 2},
                  detail::AggRow(w, h, nd, hw.sw, regs.sw_table, hw)};
  std::vector<std::array<double, 5>> band_ms(static_cast<size_t>(band_count(h, threads)));
  lap("pad");  // (the census inputs with their borders)
  parallel_bands(h, threads, [&](int y0, int y1, int b) {
    stream_rows(rows, y0, y1, keep_volumes, r, band_ms[static_cast<size_t>(b)].data());
  });
  double ms[5] = {0, 0, 0, 0, 0};  // census, cost, aggregate, dp (trellis), evidence (its record)
  for (const auto& m : band_ms)
    for (int k = 0; k < 5; ++k) ms[k] += m[static_cast<size_t>(k)];
  const char* names[5] = {"census", "cost", "aggregate", "dp", "evidence"};
  for (int k = 0; k < 5; ++k) r.stage_ms.emplace_back(names[k], ms[k]);
  t = clock::now();
  r.post = post_process(r.dp, regs, hw, &r.post_steps, threads);
  lap("post");
  // (the banded path labels objects while the words are made; the speckle stage, which the
  // labeller reads after, needs the frame's words first)
  if (band_count(h, threads) == 1 || hw.speckle_rows > 0) {
    r.out = speckle_words(make_output(r.evidence, r.post, nd, output_regs(regs), 0, threads), regs, hw);
    lap("output");
    r.objects = separate_objects(object_levels(r.out), regs, hw);
    lap("objects");
  } else {
    // (output: until the last output word; objects: the labelling left after it)
    const auto words = output_and_objects(r, regs, hw, band_count(h, threads));
    r.stage_ms.emplace_back("output", std::chrono::duration<double, std::milli>(words - t).count());
    r.stage_ms.emplace_back("objects", std::chrono::duration<double, std::milli>(clock::now() - words).count());
    t = clock::now();
  }
  // The labeller reads the words as formed (sm_outstage's m_word, or the speckle stage's
  // words where it is built, through sm_obj_level); the stream carries them smoothed.
  r.out = smooth_stream(r.out, regs.smooth_en, regs.smooth_t, threads);
  lap("smooth");
  return r;
}

}  // namespace sm
