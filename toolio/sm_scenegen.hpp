// Synthetic stereo scene generator (used by sm_scene, sm_evaluate --synthetic and the
// tests). The scene is a set of textured planar surfaces described in LEFT-view
// coordinates: a background plane (possibly slanted) and fronto-parallel rectangles and
// discs at integer disparities. Both views are ray-cast per pixel with a z-buffer (the
// nearest surface = largest disparity wins) and point-sampled textures that live on the
// surfaces, so the left-view ground truth is exact and a non-occluded left pixel at
// integer disparity d has exactly the intensity of right pixel x - d when there is no
// noise, gain/offset or camera rotation.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace sm::tools {

struct SceneParams {
  int width = 320;
  int height = 240;
  int levels = 128;  // disparities stay in 0..levels-1
  uint64_t seed = 1;
  int objects = 5;                      // rectangles / discs in front of the background
  double bg_disp = -1;                  // background disparity at (0,0); < 0: automatic (4% of levels)
  double bg_slant_x = -1e9;             // background disparity change across the width; auto if < -1e8
  double bg_slant_y = -1e9;             // ... down the height; auto if < -1e8
  double gain_l = 1.0, offset_l = 0.0;  // camera response: out = in * gain + offset
  double gain_r = 1.0, offset_r = 0.0;
  double rot_deg = 0.0;  // right camera rotated by this angle about the image centre
  double vshift = 0.0;   // ... and shifted down by this many pixels
  double noise = 0.0;    // Gaussian noise sigma (grey levels), both views
  // The rectified camera (both > 0, or both 0 = none): written into calib.json's "camera"
  // with the principal point at the image centre ((W-1)/2, (H-1)/2), so the true depth
  // of a pixel is focal_px * baseline_m / gt (metres).
  double focal_px = 0;
  double baseline_m = 0;
};

struct SyntheticScene {
  cv::Mat left, right;  // CV_8UC1; right is the RAW right camera image (with rot/vshift)
  cv::Mat gt;           // CV_32F left-view disparity (exact, every pixel known)
  cv::Mat nonocc;       // CV_8UC1, 255 where the left pixel is visible in the right view
  // Homographies of the right camera (3x3, row-major, pixel coordinates):
  // raw = H_raw_from_rect * rect, rect = H_rect_from_raw * raw. Left camera: identity.
  cv::Matx33d h_raw_from_rect = cv::Matx33d::eye();
  cv::Matx33d h_rect_from_raw = cv::Matx33d::eye();
  double min_disp = 0, max_disp = 0;  // over gt
};

// Throws std::invalid_argument on impossible parameters.
SyntheticScene render_scene(const SceneParams& p);

// An object render_scene places in front of the background (left-view coordinates):
// a rectangle [cx - rx, cx + rx) x [cy - ry, cy + ry) or the disc (ellipse) of those
// radii, fronto-parallel at an integer disparity. Nearer objects may hide parts of it.
struct PlacedObject {
  bool disc = false;
  double cx = 0, cy = 0, rx = 0, ry = 0;
  int disp = 0;
};
std::vector<PlacedObject> placed_objects(const SceneParams& p);

// Writes left.png right.png gt.png (16-bit, value = d * 256) nonocc.png scale.txt
// ("256 levels"), camera.json (homographies, gains) and calib.json (the right camera's
// homography as rectifier grids and, when p gives one, the camera, model/calib_file.hpp)
// into dir (created). Every file
// is written under a temporary name and renamed.
constexpr int kGtScale = 256;
void write_scene(const SyntheticScene& s, const SceneParams& p, const std::string& dir, bool with_nonocc = true);

}  // namespace sm::tools
