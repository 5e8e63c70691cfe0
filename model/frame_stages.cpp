#include "frame_stages.hpp"

#include "evidence.hpp"
#include "outword.hpp"
#include "smooth.hpp"
#include "speckle.hpp"

namespace sm {

PipelineResult run_frame_stages(const Image8& left, const Image8& right, const HwConfig& hw, const Regs& regs,
                                int threads) {
  hw.validate();
  validate_regs(regs, hw);
  PipelineResult r;
  r.bl = brightness(left, regs.gain_l, regs.offset_l);
  r.br = brightness(right, regs.gain_r, regs.offset_r);
  r.rl = rectify(r.bl, regs.grid_l, regs.rect_enable, hw);
  r.rr = rectify(r.br, regs.grid_r, regs.rect_enable, hw);
  r.raw =
      matching_cost(census_transform(r.rl, hw, threads), census_transform(r.rr, hw, threads), r.rl, r.rr, hw, threads);
  r.agg = sw_aggregate(r.raw, r.rl, regs.sw_table, hw, threads);
  r.dp = trellis_dp_edge(r.agg, r.rl, regs.occ, regs.occ_edge, regs.edge_t, hw, threads);
  r.post = post_process(r.dp, regs, hw, &r.post_steps, threads);
  r.evidence = evidence_frame(r.agg, r.rl, regs.occ, regs.occ_edge, regs.edge_t, hw);
  r.out = speckle_words(make_output(r.evidence, r.post, hw.disp, output_regs(regs), 0, threads), regs, hw);
  r.objects = separate_objects(object_levels(r.out), regs, hw);
  r.out = smooth_stream(r.out, regs.smooth_en, regs.smooth_t, threads);
  return r;
}

}  // namespace sm
