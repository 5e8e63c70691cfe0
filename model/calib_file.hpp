// Calibration file: the rectifier register contents of a stereo rig at one active image
// size, as the calibration tool writes them and the test harness loads them before
// writing the grids over AXI4-Lite (docs/calibration.md).
#pragma once

#include <cstdint>
#include <string>

#include "sm_types.hpp"

namespace sm {

struct CalibFile {
  int width = 0;  // active image size the grids are for
  int height = 0;
  int rect_radius_needed = 0;  // line-buffer radius the rig needs (informational)
  RectGrid left, right;        // source positions, Q.5, RectGrid::points_w/h(width/height)
};

// Throws std::runtime_error naming the file and the problem.
CalibFile load_calib(const std::string& path);
void save_calib(const std::string& path, const CalibFile& c);

// Grid memory of sm_rectify: points per grid row in the address space, the smallest power
// of two >= max(4, ceil(max_width / 16) + 1), so that a point index is {gy, gx}.
int grid_gwmax(int max_width);
int grid_ghmax(int max_height);
// grid_waddr of point (gx, gy) in bank `bank`: {bank, gy, gx}.
uint32_t grid_waddr(const HwConfig& hw, int bank, int gx, int gy);
// grid_wdata of point (gx, gy): {sy[15:0], sx[15:0]}.
uint32_t grid_wdata(const RectGrid& g, int gx, int gy);

}  // namespace sm
