// bench_stage_accuracy: bad-1.0 of the reference model after each stage of the
// post-processing chain (DP alone, after filter 1 = 5x1 vertical median, filter 2 = 3x3
// median, filter 3 = 5x3 median) on every scene of a dataset, paper configuration
// (CENSUS 15, SW 5, default registers) with --levels levels. docs/performance.md.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "toolio/sm_io.hpp"
#include "pipeline.hpp"

namespace {

int run(int argc, char** argv) {
  std::string dataset, json_path;
  int levels = 128;
  CLI::App app{"bad-1.0 of the model after each post-processing stage"};
  app.add_option("dataset", dataset, "dataset folder or one scene folder")->required();
  app.add_option("--levels", levels, "disparity levels (even, 4..254)")->capture_default_str();
  app.add_option("--json", json_path, "write the table as JSON");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::check_levels("--levels", levels);
  sm::tools::quiet_opencv();
  const auto scenes = sm::tools::list_scenes(dataset);
  if (scenes.empty()) throw sm::tools::ToolError(fmt::format("{}: no scene folders", dataset));
  const char* names[] = {"DP alone", "+ band filter", "+ 5x1 vertical median", "+ 3x3 median", "+ 5x3 median (output)"};
  constexpr int kSteps = 5;
  std::vector<double> sum(kSteps, 0.0);
  nlohmann::json js;
  fmt::print("| scene | size | {} | {} | {} | {} | {} |\n|---|---|---|---|---|---|---|\n", names[0], names[1], names[2],
             names[3], names[4]);
  for (const auto& dir : scenes) {
    const sm::tools::Scene sc = sm::tools::load_scene(dir);
    sm::HwConfig hw;
    hw.disp = levels;
    hw.max_width = sc.left.cols;
    hw.max_height = sc.left.rows;
    const sm::Regs regs = sm::Regs::defaults(hw);
    const sm::PipelineResult r =
        sm::run_pipeline(sm::tools::to_image8(sc.left), sm::tools::to_image8(sc.right), hw, regs, false);
    std::vector<const sm::DispImage*> st{&r.dp};
    for (const auto& s : r.post_steps) st.push_back(&s);
    if (st.size() != kSteps) throw sm::tools::ToolError("expected four post-processing steps");
    if (*st.back() != r.post) throw sm::tools::ToolError("last step differs from the output");
    std::string row = fmt::format("| {} | {}x{} |", sc.name, sc.left.cols, sc.left.rows);
    for (int k = 0; k < kSteps; ++k) {
      const double b = sm::tools::bad1(sm::tools::disp_to_float(*st[k]), sc.gt, sc.nonocc).bad_pct();
      sum[k] += b;
      row += fmt::format(" {:.2f} |", b);
      js[sc.name][names[k]] = b;
    }
    fmt::print("{}\n", row);
  }
  std::string row = "| mean | |";
  for (int k = 0; k < kSteps; ++k) {
    row += fmt::format(" {:.2f} |", sum[k] / scenes.size());
    js["mean"][names[k]] = sum[k] / scenes.size();
  }
  fmt::print("{}\n", row);
  if (!json_path.empty()) sm::tools::write_text_atomic(json_path, js.dump(2) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("bench_stage_accuracy", run, argc, argv); }
