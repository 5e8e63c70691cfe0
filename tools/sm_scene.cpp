// sm_scene: deterministic synthetic stereo pair with exact left-view ground truth, in the
// dataset layout of ../shared/datasets (left.png right.png gt.png nonocc.png scale.txt)
// plus camera.json (right-camera homography, gains) for rectifier tests.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "toolio/sm_io.hpp"
#include "toolio/sm_scenegen.hpp"

int main(int argc, char** argv) {
  sm::tools::SceneParams p;
  std::string out;
  bool no_nonocc = false, verbose = false;
  CLI::App app{"Synthetic stereo scene generator (exact left-view ground truth)"};
  app.add_option("--out", out, "output directory (created)")->required();
  app.add_option("--width", p.width, "image width")->capture_default_str();
  app.add_option("--height", p.height, "image height")->capture_default_str();
  app.add_option("--levels", p.levels, "disparity levels (gt stays in 0..levels-1)")->capture_default_str();
  app.add_option("--seed", p.seed, "random seed (same seed -> same bytes)")->capture_default_str();
  app.add_option("--objects", p.objects, "rectangles/discs in front of the background")->capture_default_str();
  app.add_option("--bg-disp", p.bg_disp, "background disparity at (0,0) (default 4% of levels)");
  app.add_option("--bg-slant-x", p.bg_slant_x, "background disparity change across the width (default 10% of levels)");
  app.add_option("--bg-slant-y", p.bg_slant_y, "background disparity change down the height (default 12% of levels)");
  app.add_option("--gain-l", p.gain_l, "left camera gain")->capture_default_str();
  app.add_option("--offset-l", p.offset_l, "left camera offset (grey levels)")->capture_default_str();
  app.add_option("--gain-r", p.gain_r, "right camera gain")->capture_default_str();
  app.add_option("--offset-r", p.offset_r, "right camera offset (grey levels)")->capture_default_str();
  app.add_option("--rot-deg", p.rot_deg, "right camera rotation about the image centre (degrees)")
      ->capture_default_str();
  app.add_option("--vshift", p.vshift, "right camera vertical offset (pixels)")->capture_default_str();
  app.add_option("--noise", p.noise, "Gaussian noise sigma (grey levels)")->capture_default_str();
  app.add_option("--focal-px", p.focal_px,
                 "rectified focal length (px) written into calib.json's camera, with --baseline-m: true depth = "
                 "focal * baseline / gt");
  app.add_option("--baseline-m", p.baseline_m, "camera baseline (m) written into calib.json's camera");
  app.add_flag("--no-nonocc", no_nonocc, "do not write nonocc.png");
  app.add_flag("-v,--verbose", verbose, "print a summary");
  CLI11_PARSE(app, argc, argv);
  try {
    sm::tools::quiet_opencv();
    const auto s = sm::tools::render_scene(p);
    sm::tools::write_scene(s, p, out, !no_nonocc);
    if (verbose)
      fmt::print(
          "sm_scene: {}x{} levels {} seed {} objects {}: disparity {:.2f}..{:.2f}, {:.1f}% visible "
          "-> {}\n",
          p.width, p.height, p.levels, p.seed, p.objects, s.min_disp, s.max_disp,
          100.0 * cv::countNonZero(s.nonocc) / (p.width * p.height), out);
  } catch (const std::exception& e) {
    fmt::print(stderr, "sm_scene: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
