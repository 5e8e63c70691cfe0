// sm_scene: deterministic synthetic stereo pair with exact left-view ground truth, in the
// dataset layout of ../shared/datasets (left.png right.png gt.png nonocc.png scale.txt)
// plus camera.json (right-camera homography, gains) for rectifier tests.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <exception>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_scenegen.hpp"

namespace {

using sm::tools::finite;
using sm::tools::finite_in;
using sm::tools::int_in;

int run(int argc, char** argv) {
  sm::tools::SceneParams p;
  std::string out;
  bool no_nonocc = false, verbose = false;
  CLI::App app{"Synthetic stereo scene generator (exact left-view ground truth)"};
  app.add_option("--out", out, "output directory (created)")->required();
  app.add_option("--width", p.width, "image width")->check(int_in(16, 4095))->capture_default_str();
  app.add_option("--height", p.height, "image height")->check(int_in(16, 4095))->capture_default_str();
  app.add_option("--levels", p.levels, "disparity levels (gt stays in 0..levels-1)")
      ->check(int_in(2, 255))
      ->capture_default_str();
  app.add_option("--seed", p.seed, "random seed (same seed -> same bytes)")
      ->check(int_in(0, INT64_MAX))
      ->capture_default_str();
  app.add_option("--objects", p.objects, "rectangles/discs in front of the background")
      ->check(int_in(0, 64))
      ->capture_default_str();
  app.add_option("--bg-disp", p.bg_disp, "background disparity at (0,0) (default 4% of levels)")
      ->check(finite_in(0, 254));
  app.add_option("--bg-slant-x", p.bg_slant_x, "background disparity change across the width (default 10% of levels)")
      ->check(finite());
  app.add_option("--bg-slant-y", p.bg_slant_y, "background disparity change down the height (default 12% of levels)")
      ->check(finite());
  app.add_option("--gain-l", p.gain_l, "left camera gain")->check(finite_in(0, 100))->capture_default_str();
  app.add_option("--offset-l", p.offset_l, "left camera offset (grey levels)")
      ->check(finite_in(-255, 255))
      ->capture_default_str();
  app.add_option("--gain-r", p.gain_r, "right camera gain")->check(finite_in(0, 100))->capture_default_str();
  app.add_option("--offset-r", p.offset_r, "right camera offset (grey levels)")
      ->check(finite_in(-255, 255))
      ->capture_default_str();
  app.add_option("--rot-deg", p.rot_deg, "right camera rotation about the image centre (degrees)")
      ->check(finite_in(-90, 90))
      ->capture_default_str();
  app.add_option("--vshift", p.vshift, "right camera vertical offset (pixels)")
      ->check(finite_in(-4095, 4095))
      ->capture_default_str();
  app.add_option("--noise", p.noise, "Gaussian noise sigma (grey levels)")
      ->check(finite_in(0, 255))
      ->capture_default_str();
  app.add_option("--focal-px", p.focal_px,
                 "rectified focal length (px) written into calib.json's camera, with --baseline-m: true depth = "
                 "focal * baseline / gt")
      ->check(finite_in(0, 1e6));
  app.add_option("--baseline-m", p.baseline_m, "camera baseline (m) written into calib.json's camera")
      ->check(finite_in(0, 1e3));
  app.add_flag("--no-nonocc", no_nonocc, "do not write nonocc.png");
  app.add_flag("-v,--verbose", verbose, "print a summary");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::check_output_folder("--out", out);
  sm::tools::quiet_opencv();
  const auto s = sm::tools::render_scene(p);
  sm::tools::write_scene(s, p, out, !no_nonocc);
  if (verbose)
    fmt::print(
        "sm_scene: {}x{} levels {} seed {} objects {}: disparity {:.2f}..{:.2f}, {:.1f}% visible "
        "-> {}\n",
        p.width, p.height, p.levels, p.seed, p.objects, s.min_disp, s.max_disp,
        100.0 * cv::countNonZero(s.nonocc) / (p.width * p.height), out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_scene", run, argc, argv); }
