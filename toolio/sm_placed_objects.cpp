#include "sm_placed_objects.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "outword.hpp"
#include "sm_io.hpp"

namespace sm::tools {

namespace {

PlacedCheck box_of(const PlacedObject& o, const SceneParams& p) {
  PlacedCheck c;
  c.obj = o;
  c.x0 = std::max(0, static_cast<int>(std::floor(o.cx - o.rx)));
  c.x1 = std::min(p.width - 1, static_cast<int>(std::ceil(o.cx + o.rx)));
  c.y0 = std::max(0, static_cast<int>(std::floor(o.cy - o.ry)));
  c.y1 = std::min(p.height - 1, static_cast<int>(std::ceil(o.cy + o.ry)));
  return c;
}

bool reports(const Object& l, const PlacedCheck& c) {
  return std::abs(static_cast<int>(l.mean_disp) - c.obj.disp) <= 2 && l.x0 <= c.x1 && l.x1 >= c.x0 && l.y0 <= c.y1 &&
         l.y1 >= c.y0;
}

// Counts the pixels of c's box that show the object in both views (a pixel the right
// camera cannot see has nothing to match), and those the post filters and the output word
// give its disparity (within 2).
void count_pixels(PlacedCheck& c, const SyntheticScene& s, const PipelineResult& res) {
  auto near_disp = [&](int level) { return std::abs(level - c.obj.disp) <= 2; };
  for (int y = c.y0; y <= c.y1; ++y)
    for (int x = c.x0; x <= c.x1; ++x) {
      if (s.gt.at<float>(y, x) != static_cast<float>(c.obj.disp) || s.nonocc.at<uint8_t>(y, x) == 0) continue;
      ++c.visible;
      c.matched += near_disp(static_cast<int>(disp_value(res.post.at(x, y))));
      const uint32_t w = res.out.at(x, y);
      c.kept += out_valid(w) && near_disp(static_cast<int>((out_q4(w) + 8) >> 4));
    }
}

}  // namespace

PipelineResult run_on_scene(const SceneParams& p, const SyntheticScene& s, const HwConfig& hw, Regs r) {
  r.width = p.width;
  r.height = p.height;
  r.grid_l = RectGrid::identity(p.width, p.height);
  r.grid_r = r.grid_l;
  return run_pipeline(to_image8(s.left), to_image8(s.right), hw, r, false);
}

std::vector<PlacedCheck> check_placed_objects(const SceneParams& p, const SyntheticScene& s, const PipelineResult& res,
                                              int min_pixels, int near) {
  std::vector<PlacedCheck> out;
  const std::vector<Object>& listed = res.objects.objects;
  for (const PlacedObject& o : placed_objects(p)) {
    PlacedCheck c = box_of(o, p);
    count_pixels(c, s, res);
    c.counts = c.visible >= min_pixels && o.disp >= near;
    c.found = std::any_of(listed.begin(), listed.end(), [&](const Object& l) { return reports(l, c); });
    out.push_back(c);
  }
  return out;
}

}  // namespace sm::tools
