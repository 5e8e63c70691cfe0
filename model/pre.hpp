// Pre-processing stages of the reference model (docs/algorithm.md, sections 1-2):
// brightness control and grid-based rectification, plus helpers the calibration tool
// uses to turn a dense rectification map into the register grid.
#pragma once

#include <cstdint>
#include <vector>

#include "sm_types.hpp"

namespace sm {

// Section 1: out = clamp(((in * gain + 128) >> 8) + offset, 0, 255). gain is Q2.8
// (10 bits used), offset is signed 9 bits (-256..255).
Image8 brightness(const Image8& in, uint16_t gain, int16_t offset);

// Section 2: bilinear resampling at the grid-interpolated source positions. A grid with
// gw == 0 means identity; enable == false passes the image through. Taps outside the
// image or more than hw.rect_radius rows from the output row read 0. Throws
// std::invalid_argument when the grid does not match the image size.
Image8 rectify(const Image8& in, const RectGrid& grid, bool enable, const HwConfig& hw);

// Source position of output pixel (x, y) in Q.4 as the hardware interpolates it.
void rect_source_q4(const RectGrid& g, int x, int y, int& sx, int& sy);

// Samples a dense source map (map_w x map_h floats, row-major, e.g. OpenCV's
// initUndistortRectifyMap output) at the grid points of a width x height image, rounding
// to Q.5 with saturation to int16. The map must cover the grid extent
// ((gw-1)*16+1 x (gh-1)*16+1, beyond width x height when it is not a multiple of 16);
// throws std::invalid_argument otherwise.
RectGrid grid_from_maps(const std::vector<float>& mapx, const std::vector<float>& mapy, int map_w, int map_h, int width,
                        int height);

// The RECT_RADIUS a grid needs: the largest |r - y| over every bilinear tap row r with a
// non-zero weight that lies inside the image (so the second row of a tap pair counts
// as +1). With hw.rect_radius >= this value rectify() equals an unlimited window.
int rect_radius_needed(const RectGrid& g, int width, int height);

}  // namespace sm
