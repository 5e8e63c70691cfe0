// bench_icarus_vectors: stimulus and expected output for the Icarus Verilog speed run
// (bench/sm_bench_tb.v): in.hex holds one 16-bit AXI4-Stream word per pixel
// ({right, left}, frames back to back), expected.hex the reference model's output word
// per pixel (the same frames, rectifier bypassed, every other register at its reset
// value) so the script can check the Icarus run bit for bit.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "pipeline.hpp"

namespace {

int run(int argc, char** argv) {
  std::string scene_dir, out;
  int frames = 2;
  sm::HwConfig hw;
  CLI::App app{"Stimulus + expected output hex files for the Icarus testbench"};
  app.add_option("--scene", scene_dir, "scene folder (left.png right.png), resized to MAX_WIDTH x MAX_HEIGHT")
      ->required();
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--frames", frames, "frames (the pair repeated)")
      ->check(sm::tools::int_in(1, 100))
      ->capture_default_str();
  app.add_option("--max-width", hw.max_width)->capture_default_str();
  app.add_option("--max-height", hw.max_height)->capture_default_str();
  app.add_option("--disp", hw.disp)->capture_default_str();
  app.add_option("--census", hw.census)->capture_default_str();
  app.add_option("--sw", hw.sw)->capture_default_str();
  app.add_option("--rect-radius", hw.rect_radius)->capture_default_str();
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();
  hw.validate();
  const sm::tools::Scene sc = sm::tools::load_scene(scene_dir);
  const cv::Size sz(hw.max_width, hw.max_height);
  cv::Mat l = sc.left, r = sc.right;
  if (l.size() != sz) {
    cv::resize(sc.left, l, sz, 0, 0, cv::INTER_AREA);
    cv::resize(sc.right, r, sz, 0, 0, cv::INTER_AREA);
  }
  const sm::Image8 li = sm::tools::to_image8(l), ri = sm::tools::to_image8(r);
  sm::Regs regs = sm::Regs::defaults(hw);
  regs.rect_enable = false;  // the testbench writes RECT_ENABLE = 0 and nothing else
  const sm::PipelineResult res = sm::run_pipeline(li, ri, hw, regs, false);
  std::string in_txt, exp_txt;
  for (int f = 0; f < frames; ++f)
    for (int y = 0; y < li.h; ++y)
      for (int x = 0; x < li.w; ++x) {
        in_txt += fmt::format("{:04x}\n", li.at(x, y) | (ri.at(x, y) << 8));
        exp_txt += fmt::format("{:08x}\n", res.out.at(x, y));
      }
  sm::tools::write_text_atomic(out + "/in.hex", in_txt);
  sm::tools::write_text_atomic(out + "/expected.hex", exp_txt);
  fmt::print("{} frame(s) of {}x{} -> {}/in.hex, {}/expected.hex\n", frames, li.w, li.h, out, out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("bench_icarus_vectors", run, argc, argv); }
