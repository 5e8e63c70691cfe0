// stereo_sim's check against the reference model (sm_sim_check.hpp).
#include "sm_sim_check.hpp"

#include <fmt/format.h>

namespace sm::simapp {

namespace {

// Counts one mismatch of frame f; the run's first one is described by `what`.
template <class What>
void count_mismatch(ModelCheck& c, size_t f, const What& what) {
  ++c.frame_mismatches[f];
  if (c.mismatches++ == 0) c.first_mismatch = what();
}

// Frame f (width x height) of the RTL against the model's.
void check_frame(size_t f, int width, int height, const PipelineResult& m, const SimResult& res, ModelCheck& c) {
  const DispImage& exp = m.post;
  const DispImage& got = res.frames[f];
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (exp.at(x, y) != got.at(x, y))
        count_mismatch(c, f, [&] {
          return fmt::format("frame {} x {} y {}: expected 0x{:04x} got 0x{:04x}", f, x, y, exp.at(x, y), got.at(x, y));
        });
  const std::vector<uint32_t> want = object_packet(m.objects, false);
  if (f < res.object_packets.size() && res.object_packets[f].words != want)
    count_mismatch(c, f, [&] { return fmt::format("frame {}: object packet differs", f); });
}

}  // namespace

ModelCheck check_against_model(bool no_check, const HwConfig& hw, const SimInput& in, const RegisterPlan& plan,
                               const SimResult& res) {
  const size_t nframes = in.frames.size();
  ModelCheck c;
  c.frame_mismatches.assign(nframes, 0);
  if (no_check) return c;
  c.done = true;
  for (size_t f = 0; f < nframes; ++f) {
    c.model.push_back(run_pipeline(in.frames[f].first, in.frames[f].second, hw, plan.regs[f], false));
    check_frame(f, plan.width, plan.height, c.model.back(), res, c);
  }
  if (res.object_packets.size() < nframes && c.mismatches++ == 0)
    c.first_mismatch = fmt::format("{} object packets for {} frames", res.object_packets.size(), nframes);
  return c;
}

}  // namespace sm::simapp
