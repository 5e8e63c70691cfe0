// bench_scale_dataset: writes a copy of a stereo dataset (../shared/datasets layout) at
// the IP's active size, so the RTL simulation (stereo_sim, which accepts at most
// MAX_WIDTH x MAX_HEIGHT) and the model can be scored on exactly the same pixels.
// Images are resized the way stereo_sim resizes its input (grey, INTER_AREA); the
// ground truth and the mask are resampled nearest-neighbour and the disparities scaled
// by the horizontal factor. gt.png is written 16-bit with scale 256.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"

namespace {

int run(int argc, char** argv) {
  std::string dataset, out;
  int width = 320, height = 240;
  CLI::App app{"Resize a stereo dataset to the IP's active size (for RTL-vs-model accuracy)"};
  app.add_option("dataset", dataset, "dataset folder or one scene folder")->required();
  app.add_option("--out", out, "output folder (one subfolder per scene)")->required();
  app.add_option("--width", width, "target width")->check(sm::tools::int_in(16, 4096))->capture_default_str();
  app.add_option("--height", height, "target height")->check(sm::tools::int_in(16, 4096))->capture_default_str();
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();
  const auto scenes = sm::tools::list_scenes(dataset);
  if (scenes.empty()) throw sm::tools::ToolError(fmt::format("{}: no scene folders", dataset));
  for (const auto& dir : scenes) {
    const sm::tools::Scene sc = sm::tools::load_scene(dir);
    const cv::Size sz(width, height);
    const double sx = static_cast<double>(width) / sc.left.cols;
    cv::Mat l, r, gt, mask;
    cv::resize(sc.left, l, sz, 0, 0, cv::INTER_AREA);
    cv::resize(sc.right, r, sz, 0, 0, cv::INTER_AREA);
    cv::resize(sc.gt, gt, sz, 0, 0, cv::INTER_NEAREST);
    cv::Mat gt16;
    gt.convertTo(gt16, CV_16U, 256.0 * sx);  // rounds and saturates
    const std::string od = (std::filesystem::path(out) / sc.name).string();
    std::filesystem::create_directories(od);
    sm::tools::write_image_atomic(od + "/left.png", l);
    sm::tools::write_image_atomic(od + "/right.png", r);
    sm::tools::write_image_atomic(od + "/gt.png", gt16);
    if (!sc.nonocc.empty()) {
      cv::resize(sc.nonocc, mask, sz, 0, 0, cv::INTER_NEAREST);
      sm::tools::write_image_atomic(od + "/nonocc.png", mask);
    }
    const int levels = static_cast<int>(std::ceil(sc.levels * sx));
    sm::tools::write_text_atomic(od + "/scale.txt", fmt::format("256 {}\n", levels));
    fmt::print("{}: {}x{} -> {}x{} (disparity x{:.3f}, {} levels)\n", sc.name, sc.left.cols, sc.left.rows, width,
               height, sx, levels);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("bench_scale_dataset", run, argc, argv); }
