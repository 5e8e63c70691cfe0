#include "pipeline.hpp"

#include <chrono>
#include <stdexcept>

#include <fmt/format.h>

namespace sm {

void validate_regs(const Regs& r, const HwConfig& hw) {
  auto bad = [](const std::string& m) { throw std::invalid_argument(m); };
  if (r.width < 16 || r.width > hw.max_width)
    bad(fmt::format("width {} outside 16..{}", r.width, hw.max_width));
  if (r.height < 16 || r.height > hw.max_height)
    bad(fmt::format("height {} outside 16..{}", r.height, hw.max_height));
  if (r.gain_l > 1023 || r.gain_r > 1023) bad("gain above 1023 (10-bit Q2.8)");
  if (r.offset_l < -256 || r.offset_l > 255 || r.offset_r < -256 || r.offset_r > 255)
    bad("offset outside -256..255 (9-bit signed)");
  for (uint8_t c : r.sw_table)
    if (c > 3) bad("sw_table code above 3");
  for (const RectGrid* g : {&r.grid_l, &r.grid_r})
    if (g->gw != 0 && (g->gw != RectGrid::points_w(r.width) || g->gh != RectGrid::points_h(r.height)))
      bad(fmt::format("rectification grid is {}x{} points, the active size needs {}x{}", g->gw,
                      g->gh, RectGrid::points_w(r.width), RectGrid::points_h(r.height)));
}

PipelineResult run_pipeline(const Image8& left, const Image8& right, const HwConfig& hw,
                            const Regs& regs, bool keep_volumes) {
  hw.validate();
  validate_regs(regs, hw);
  if (left.w != regs.width || left.h != regs.height || right.w != regs.width ||
      right.h != regs.height)
    throw std::invalid_argument(fmt::format("images {}x{} / {}x{} do not match the active size {}x{}",
                                            left.w, left.h, right.w, right.h, regs.width,
                                            regs.height));
  PipelineResult r;
  using clock = std::chrono::steady_clock;
  auto t = clock::now();
  auto lap = [&](const char* name) {
    auto now = clock::now();
    r.stage_ms.emplace_back(name, std::chrono::duration<double, std::milli>(now - t).count());
    t = now;
  };
  r.bl = brightness(left, regs.gain_l, regs.offset_l);
  r.br = brightness(right, regs.gain_r, regs.offset_r);
  lap("brightness");
  r.rl = rectify(r.bl, regs.grid_l, regs.rect_enable, hw);
  r.rr = rectify(r.br, regs.grid_r, regs.rect_enable, hw);
  lap("rectify");
  const CensusImage cl = census_transform(r.rl, hw);
  const CensusImage cr = census_transform(r.rr, hw);
  lap("census");
  CostVolume raw = hamming_cost(cl, cr, hw);
  lap("cost");
  CostVolume agg = sw_aggregate(raw, r.rl, regs.sw_table, hw);
  lap("aggregate");
  r.dp = trellis_dp(agg, regs.occ, hw);
  lap("dp");
  r.post = post_process(r.dp, regs, hw, &r.post_steps);
  lap("post");
  r.objects = separate_objects(r.post, regs, hw);
  lap("objects");
  if (keep_volumes) {
    r.raw = std::move(raw);
    r.agg = std::move(agg);
  }
  return r;
}

}  // namespace sm
