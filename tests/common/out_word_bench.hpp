// The block tests of the stages after the output word (sm_out_smooth, sm_out_support):
// their stimulus words and the check of each output word against the model.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <vector>

#include "outword.hpp"
#include "speckle.hpp"

namespace sm::test {

// Slanted planes a few levels apart with +-noise in the Q.4 value, a tenth invalid (their
// failed rules, now and then the speckle stage's bit), now and then a word anywhere in
// 0 .. 16 (DISP - 1) (anywhere: everywhere), every confidence byte.
inline OutImage random_out_words(std::mt19937& rng, int w, int h, int nd, bool anywhere, int noise) {
  OutImage m(w, h);
  const int top = 16 * (nd - 1);
  const int step = 16 * (1 + static_cast<int>(rng() % 4));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int base = (x * 3 / std::max(1, w / 4)) * step + y * 2 + static_cast<int>(rng() % (2 * noise)) - noise;
      const int q = anywhere || rng() % 12 == 0 ? static_cast<int>(rng() % (top + 1)) : std::clamp(base, 0, top);
      const bool valid = rng() % 10 != 0;
      const unsigned byte = rng() & 0xff;  // the confidence, or an invalid word's failed rules
      m.at(x, y) =
          make_out_word(valid, byte, static_cast<unsigned>(q), byte) | (!valid && (byte & 64) ? kOutSpeckle : 0);
    }
  return m;
}

// Checks a real output word `got` (position o) against the model's frames `want` and its
// latency against the documented one: k ce's taken so far, beat_of as beat_index gives it.
template <class Test, class Out>
void check_out_word(Test& t, const Out& o, size_t k, const std::vector<std::vector<long>>& beat_of, int w, long latency,
                    const std::vector<OutImage>& want, uint32_t got) {
  const uint32_t e = want[o.frame].at(o.x, o.y);
  const long lat = static_cast<long>(k - 1) - beat_of[o.frame][static_cast<size_t>(o.y) * w + o.x];
  if (lat != latency)
    t.fail(
        fmt::format("latency at w {} frame {} x {} y {}: {} beats, documented {}", w, o.frame, o.x, o.y, lat, latency));
  else
    t.check(got == e, [&] {
      return fmt::format("w {} frame {} x {} y {} expected {:#010x} got {:#010x}", w, o.frame, o.x, o.y, e, got);
    });
}

}  // namespace sm::test
