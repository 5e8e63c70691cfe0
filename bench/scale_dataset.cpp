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
#include "toolio/sm_outputs.hpp"

namespace {

// One scene at sz into folder od, staged in outs; prints its line.
void scale_scene(const sm::tools::Scene& sc, const cv::Size& sz, const std::string& od, sm::tools::OutputSet& outs) {
  const double sx = static_cast<double>(sz.width) / sc.left.cols;
  cv::Mat l, r, gt, gt16, mask;
  cv::resize(sc.left, l, sz, 0, 0, cv::INTER_AREA);
  cv::resize(sc.right, r, sz, 0, 0, cv::INTER_AREA);
  cv::resize(sc.gt, gt, sz, 0, 0, cv::INTER_NEAREST);
  gt.convertTo(gt16, CV_16U, 256.0 * sx);  // rounds and saturates
  const auto image = [&](const char* name, const cv::Mat& m) {
    outs.write(
        od + "/" + name, [&](const std::string& t) { sm::tools::write_image_atomic(t, m); }, true);
  };
  image("left.png", l);
  image("right.png", r);
  image("gt.png", gt16);
  if (!sc.nonocc.empty()) {
    cv::resize(sc.nonocc, mask, sz, 0, 0, cv::INTER_NEAREST);
    image("nonocc.png", mask);
  }
  const int levels = static_cast<int>(std::ceil(sc.levels * sx));
  outs.write(
      od + "/scale.txt",
      [&](const std::string& t) { sm::tools::write_text_atomic(t, fmt::format("256 {}\n", levels)); }, true);
  fmt::print("{}: {}x{} -> {}x{} (disparity x{:.3f}, {} levels)\n", sc.name, sc.left.cols, sc.left.rows, sz.width,
             sz.height, sx, levels);
}

int run(int argc, char** argv) {
  std::string dataset, out;
  int width = 320, height = 240;
  CLI::App app{"Resize a stereo dataset to the IP's active size (for RTL-vs-model accuracy)"};
  app.add_option("dataset", dataset, "dataset folder or one scene folder")->required();
  app.add_option("--out", out, "output folder (one subfolder per scene)")->required();
  app.add_option("--width", width, "target width")->check(sm::tools::int_in(16, 4095))->capture_default_str();
  app.add_option("--height", height, "target height")->check(sm::tools::int_in(16, 4095))->capture_default_str();
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::check_output_folder("--out", out);
  sm::tools::quiet_opencv();
  const auto scenes = sm::tools::list_scenes(dataset);
  if (scenes.empty()) throw sm::tools::ToolError(fmt::format("{}: no scene folders", dataset));
  // all scenes or none: a scene that fails leaves no scaled copy of the ones before it
  sm::tools::OutputSet outs;
  for (const auto& dir : scenes) {
    const sm::tools::Scene sc = sm::tools::load_scene(dir);
    scale_scene(sc, cv::Size(width, height), (std::filesystem::path(out) / sc.name).string(), outs);
  }
  outs.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("bench_scale_dataset", run, argc, argv); }
