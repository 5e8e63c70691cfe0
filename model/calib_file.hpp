// Calibration file: the rectifier register contents of a stereo rig at one active image
// size, as the calibration tool writes them and the test harness loads them before
// writing the grids over AXI4-Lite (docs/calibration.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sm_types.hpp"

namespace sm {

// The rectified left camera, for metric depth (docs/calibration.md, "Camera"): a pixel
// (x, y) of disparity d > 0 lies at Z = f_px * baseline_m / d metres, X = (x - cx) Z / f_px,
// Y = (y - cy) Z / f_px (camera frame: X right, Y down, Z forward).
struct RectCamera {
  double f_px = 0;        // rectified focal length (pixels at the active image size)
  double cx = 0, cy = 0;  // principal point (pixels)
  double baseline_m = 0;  // distance between the camera centres (metres, or the calibration's unit)
};

struct CalibFile {
  int width = 0;  // active image size the grids are for
  int height = 0;
  int rect_radius_needed = 0;        // line-buffer radius the rig needs (checked by check_calib_fits)
  RectGrid left, right;              // source positions, Q.5, RectGrid::points_w/h(width/height)
  std::optional<RectCamera> camera;  // key "camera"; absent in files without metric depth
};

// Throws std::runtime_error naming the file and the problem: unreadable, malformed,
// missing or unknown keys (the key named), values of the wrong type or out of range.
CalibFile load_calib(const std::string& path);
void save_calib(const std::string& path, const CalibFile& c);

// Throws std::runtime_error "<path>: 'rect_radius_needed' = N exceeds the IP's RECT_RADIUS R"
// when the rig needs more line-buffer rows than an IP built with `hw` holds.
void check_calib_fits(const std::string& path, const CalibFile& c, const HwConfig& hw);
// load_calib, then check_calib_fits: a calibration file an IP built with `hw` can hold.
CalibFile load_fitting_calib(const std::string& path, const HwConfig& hw);

// Grid memory of sm_rectify: points per grid row in the address space, the smallest power
// of two >= max(4, ceil(max_width / 16) + 1), so that a point index is {gy, gx}.
int grid_gwmax(int max_width);
int grid_ghmax(int max_height);
// grid_waddr of point (gx, gy) in bank `bank`: {bank, gy, gx}.
uint32_t grid_waddr(const HwConfig& hw, int bank, int gx, int gy);
// grid_wdata of point (gx, gy): {sy[15:0], sx[15:0]}.
uint32_t grid_wdata(const RectGrid& g, int gx, int gy);

}  // namespace sm
