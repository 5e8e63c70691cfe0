// The generator's own objects against an object list (issue 39, "objects that hold"): which
// of the objects render_scene placed a robot should be told about, and whether the list
// reports each. Shared by test_scene and bench_objects.
#pragma once

#include <vector>

#include "pipeline.hpp"
#include "sm_scenegen.hpp"

namespace sm::tools {

struct PlacedCheck {
  PlacedObject obj;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // its box in the image, inclusive
  int visible = 0;                     // pixels of the box showing it in both views (gt, nonocc)
  bool counts = false;                 // visible >= min_pixels and disparity >= near: must be reported
  bool found = false;                  // a listed object at its disparity (+-2) whose box meets its box
  int matched = 0;                     // visible pixels whose post-filter level is within 2 of its disparity
  int kept = 0;                        // ... and whose output word is valid at a level within 2 of it
};

// The model at hw with the registers r on s = render_scene(p), r's active size and
// rectification grids made the scene's (identity: the generator's views are rectified).
PipelineResult run_on_scene(const SceneParams& p, const SyntheticScene& s, const HwConfig& hw, Regs r);

// Every object placed_objects(p) gives, checked against the object list of `res`, the
// model's run on s = render_scene(p) (min_pixels and near: the OBJ_MIN_PIXELS and OBJ_NEAR
// it ran with). matched and kept tell a miss of the matcher from one of the labeller.
std::vector<PlacedCheck> check_placed_objects(const SceneParams& p, const SyntheticScene& s, const PipelineResult& res,
                                              int min_pixels, int near);

}  // namespace sm::tools
