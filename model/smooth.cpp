#include "smooth.hpp"

#include <algorithm>
#include <vector>

#include "kernels.hpp"
#include "parallel.hpp"
#include "row_support.hpp"

namespace sm {

namespace {

// A value no Q.4 disparity (0 .. 16 * 255 + 15) comes within any threshold (< 256) of:
// invalid pixels and columns outside the frame.
constexpr int16_t kFar = -8192;

// The frame as Q.4 values, kSmoothR far columns on both sides of each row (stride w + 2R).
std::vector<int16_t> padded_values(const OutImage& in) {
  const size_t pw = static_cast<size_t>(in.w + 2 * kSmoothR);
  std::vector<int16_t> q(pw * static_cast<size_t>(in.h), kFar);
  for (int y = 0; y < in.h; ++y)
    for (int x = 0; x < in.w; ++x) {
      const uint32_t v = in.at(x, y);
      q[static_cast<size_t>(y) * pw + static_cast<size_t>(x + kSmoothR)] =
          out_valid(v) ? static_cast<int16_t>(out_q4(v)) : kFar;
    }
  return q;
}

// One window row's 5 columns into the sums of the w centres: s the kept differences, k the
// kept pixels (within t), kn those within kSupportNear. nb: the row's padded values.
// (16-bit lanes and masks instead of branches: the compiler's vector loop.)
SM_HOT void add_window_row(const int16_t* nb, const int16_t* ctr, int w, int16_t t, int16_t* s, int16_t* k,
                           int16_t* kn) {
  for (int dx = 0; dx <= 2 * kSmoothR; ++dx)
    for (int x = 0; x < w; ++x) {
      const int16_t d = static_cast<int16_t>(nb[x + dx] - ctr[x]);
      const int16_t m = static_cast<int16_t>(-((d >= -t) & (d <= t)));
      const int16_t mn = static_cast<int16_t>(-((d >= -kSupportNear) & (d <= kSupportNear)));
      s[x] = static_cast<int16_t>(s[x] + (d & m));
      k[x] = static_cast<int16_t>(k[x] - m);
      kn[x] = static_cast<int16_t>(kn[x] - mn);
    }
}

// Rows y0..y1-1 of smooth_output into out; q = padded_values(in), en = smooth_en.
void smooth_rows(const OutImage& in, const std::vector<int16_t>& q, bool en, int t, int y0, int y1, OutImage& out) {
  const int w = in.w, h = in.h;
  const size_t pw = static_cast<size_t>(w + 2 * kSmoothR);
  std::vector<int16_t> s(static_cast<size_t>(w)), k(static_cast<size_t>(w)), kn(static_cast<size_t>(w));
  for (int y = y0; y < y1; ++y) {
    const int16_t* ctr = &q[static_cast<size_t>(y) * pw + kSmoothR];
    std::fill(s.begin(), s.end(), int16_t{0});
    std::fill(k.begin(), k.end(), int16_t{0});
    std::fill(kn.begin(), kn.end(), int16_t{0});
    for (int yy = std::max(0, y - kSmoothR); yy <= std::min(h - 1, y + kSmoothR); ++yy)
      add_window_row(&q[static_cast<size_t>(yy) * pw], ctr, w, static_cast<int16_t>(t), s.data(), k.data(), kn.data());
    for (int x = 0; x < w; ++x) {
      const uint32_t v = in.at(x, y);
      if (!out_valid(v)) {
        out.at(x, y) = v;
        continue;
      }
      const size_t i = static_cast<size_t>(x);
      const int qo = en ? ctr[x] + smooth_offset(s[i], k[i]) : ctr[x];
      out.at(x, y) = make_out_word(true, support_confidence(out_conf(v), k[i], kn[i]), static_cast<unsigned>(qo));
    }
  }
}

}  // namespace

int smooth_offset(int s, int k) {
  const int num = 2 * s + k, den = 2 * k;  // floor(num / den), num of either sign
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}

OutImage smooth_output(const OutImage& in, int smooth_en, int smooth_t, int threads) {
  OutImage out(in.w, in.h);
  const std::vector<int16_t> q = padded_values(in);
  parallel_bands(in.h, threads,
                 [&](int y0, int y1, int) { smooth_rows(in, q, smooth_en != 0, smooth_t, y0, y1, out); });
  return out;
}

OutImage smooth_stream(const OutImage& in, int smooth_en, int smooth_t, int threads) {
  return row_support_output(smooth_output(in, smooth_en, smooth_t, threads), threads);
}

OutImage stream_words(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int threads) {
  return smooth_stream(make_output(ev, post, nd, r, 0, threads), r.smooth_en, r.smooth_t, threads);
}

}  // namespace sm
