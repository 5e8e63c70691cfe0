// The generator's own objects against an object list (issue 39, "objects that hold"): which
// of the objects render_scene placed a robot should be told about, and whether the list
// reports each. Shared by test_scene and bench_objects.
#pragma once

#include <vector>

#include "post.hpp"
#include "sm_scenegen.hpp"

namespace sm::tools {

struct PlacedCheck {
  PlacedObject obj;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // its box in the image, inclusive
  int visible = 0;                     // pixels of the box where the ground truth is its disparity
  bool counts = false;                 // visible >= min_pixels and disparity >= near: must be reported
  bool found = false;                  // a listed object at its disparity (+-2) whose box meets its box
};

// Every object placed_objects(p) gives, checked against `listed` (s = render_scene(p);
// min_pixels and near: the OBJ_MIN_PIXELS and OBJ_NEAR the list was made with).
std::vector<PlacedCheck> check_placed_objects(const SceneParams& p, const SyntheticScene& s,
                                              const std::vector<Object>& listed, int min_pixels, int near);

}  // namespace sm::tools
