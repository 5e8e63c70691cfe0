// Metric depth and point clouds from a disparity image and the rectified left camera of
// a calibration (sm::RectCamera, model/calib_file.hpp; docs/calibration.md). Used by
// stereo_model (--depth-file, --cloud) and meant for stereo_sim's outputs.
#pragma once

#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "calib_file.hpp"

namespace sm::tools {

// The camera can turn disparity into depth: focal length and baseline finite and > 0,
// principal point finite. Throws ToolError "<what>: ..." otherwise.
void check_camera(const RectCamera& cam, const std::string& what);

// Depth in metres, CV_32F: Z = f_px * baseline_m / d for every disparity d that is finite
// and > 0 (sub-pixel values welcome); +infinity where d is invalid (negative, zero, NaN
// or infinite: disp_to_float's -1 included).
cv::Mat disparity_to_depth(const cv::Mat& disp_f, const RectCamera& cam);

// One point of the cloud: metres in the rectified left camera's frame (X right, Y down,
// Z forward) and the grey value of its pixel in the rectified left image.
struct CloudPoint {
  float x = 0, y = 0, z = 0;
  uint8_t grey = 0;
};

// The points of every pixel with a finite depth <= max_depth, in raster order:
// X = (x - cx) Z / f_px, Y = (y - cy) Z / f_px. grey is CV_8UC1 of the depth's size.
std::vector<CloudPoint> depth_to_cloud(const cv::Mat& depth, const cv::Mat& grey, const RectCamera& cam,
                                       double max_depth = std::numeric_limits<double>::infinity());

// Depth files, the format chosen by the extension (ToolError for any other):
// - .pfm: one-channel float32 metres, +infinity = invalid;
// - .png: 16-bit grey millimetres, round(Z * 1000), 0 = invalid; depths that do not fit
//   (>= 65.5355 m, or below 0.5 mm) are written as 0 too.
// Written with write_image_atomic (stage it in an OutputSet for all-or-nothing sets).
void write_depth_file(const std::string& path, const cv::Mat& depth);
// Depth as written by write_depth_file, read back as CV_32F metres, +infinity = invalid.
cv::Mat read_depth_file(const std::string& path);
// A depth file name the writer accepts (.pfm or .png, any case).
bool is_depth_file_name(const std::string& path);

// Binary little-endian PLY 1.0 of the points: "element vertex N" with properties
// float x, float y, float z (metres) and uchar intensity (the grey value), 13 bytes per
// vertex, no faces. Written under a temporary name and renamed; throws ToolError naming
// `path` when it cannot be written.
void write_ply(const std::string& path, const std::vector<CloudPoint>& points);

}  // namespace sm::tools
