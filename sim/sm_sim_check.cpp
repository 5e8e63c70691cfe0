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

}  // namespace

ModelCheck start_check(bool no_check, size_t first, size_t nframes) {
  ModelCheck c;
  c.done = !no_check;
  c.first = first;
  c.frame_mismatches.assign(nframes, 0);
  if (c.done) c.want_packets.resize(nframes);
  return c;
}

void check_frame(ModelCheck& c, size_t f, const HwConfig& hw, const Regs& regs, const StereoFrame& in,
                 const OutImage& got) {
  const bool last = f + 1 == c.frame_mismatches.size();
  if (last) c.last_input = in;
  if (!c.done) return;
  PipelineResult m = run_pipeline(in.first, in.second, hw, regs, false);
  const OutImage& exp = m.out;
  const size_t fg = c.first + f;
  for (int y = 0; y < exp.h; ++y)
    for (int x = 0; x < exp.w; ++x)
      if (exp.at(x, y) != got.at(x, y))
        count_mismatch(c, f, [&] {
          return fmt::format("frame {} x {} y {}: expected 0x{:08x} got 0x{:08x}", fg, x, y, exp.at(x, y),
                             got.at(x, y));
        });
  c.want_packets[f] = object_packet(m.objects, false);
  if (last) c.last_model = std::move(m);
}

void check_packets(ModelCheck& c, const SimResult& res) {
  if (!c.done) return;
  const size_t nframes = c.frame_mismatches.size();
  for (size_t f = 0; f < nframes && f < res.object_packets.size(); ++f)
    if (res.object_packets[f].words != c.want_packets[f])
      count_mismatch(c, f, [&] { return fmt::format("frame {}: object packet differs", c.first + f); });
  if (res.object_packets.size() < nframes && c.mismatches++ == 0)
    c.first_mismatch = fmt::format("{} object packets for {} frames", res.object_packets.size(), nframes);
}

}  // namespace sm::simapp
