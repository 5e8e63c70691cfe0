#include "outword.hpp"

#include <algorithm>
#include <stdexcept>

#include "confidence.hpp"
#include "subpix.hpp"
#include "validity.hpp"

namespace sm {

OutImage make_output(const Evidence& ev, const DispImage& post, int nd, const OutputRegs& r, int conf_variant) {
  if (post.w != ev.d.w || post.h != ev.d.h) throw std::invalid_argument("make_output: evidence and post sizes differ");
  OutImage out(post.w, post.h);
  for (int y = 0; y < post.h; ++y)
    for (int x = 0; x < post.w; ++x) {
      const DispPix p = post.at(x, y);
      int d_out = static_cast<int>(disp_value(p));
      int q4 = subpix_after_post(subpix_q4(ev, x, y, nd, r), ev.d.at(x, y), d_out);
      if (!r.occ_en && r.fill_bg && !ev.matched.at(x, y) && ev.fill_bg.at(x, y) < d_out) {
        d_out = ev.fill_bg.at(x, y);
        q4 = 16 * d_out;
      }
      q4 = std::clamp(q4, 0, 16 * (nd - 1));
      const bool valid = disp_valid(p) && valid_pixel(ev, x, y, d_out, r);
      out.at(x, y) = make_out_word(valid, confidence(ev, x, y, d_out, conf_variant), static_cast<unsigned>(q4));
    }
  return out;
}

}  // namespace sm
