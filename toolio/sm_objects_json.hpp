// The objects of an object list (model/post.hpp) in the tools' JSON outputs: stereo_sim's
// report.json (each frame's object_packet, as the IP sent it) and stereo_model
// --objects-json. Each output names the other fields in its own way (pixels / count,
// nearest_disp / max_disp); the box and the mean disparity are written the same.
#pragma once

#include <nlohmann/json.hpp>

#include "post.hpp"

namespace sm::tools {

// {"x0", "y0", "x1", "y1"} (the bounding box, inclusive) and "mean_disp" of an object.
inline nlohmann::json object_box_json(const Object& o) {
  return {{"x0", o.x0}, {"y0", o.y0}, {"x1", o.x1}, {"y1", o.y1}, {"mean_disp", o.mean_disp}};
}

}  // namespace sm::tools
