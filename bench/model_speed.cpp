// bench_model_speed: run time of the reference model (sm::run_pipeline, per stage) on
// one thread and on --threads threads against OpenCV's StereoSGBM and the census
// StereoBinarySGBM (contrib), both on one thread, on the same 320x240 pair with the
// same number of levels, in the same run; medians over --runs repetitions, interleaved
// so machine load hits every method alike.
// docs/performance.md, "Model speed".
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <ctime>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/stereo.hpp>

#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "frame_stages.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// FNV-1a over the disparity words: a fingerprint to show that a speed change left every
// output bit alone (compare the printed value before and after).
template <class T>
uint64_t fnv(const std::vector<T>& v) {
  uint64_t h = 1469598103934665603ull;
  for (auto p : v) {
    for (size_t b = 0; b < sizeof(T); ++b) {
      h ^= (static_cast<uint64_t>(p) >> (8 * b)) & 0xffu;
      h *= 1099511628211ull;
    }
  }
  return h;
}

// Wall time and the CPU time of the whole process (every thread) since construction: on a
// loaded machine the CPU time of a one-thread method barely moves while its wall time does.
double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}
struct Lap {
  Clock::time_point wall = Clock::now();
  double cpu = cpu_ms();
  // Appends the wall ms to t[name] and the CPU ms to t["cpu." + name].
  void to(std::map<std::string, std::vector<double>>& t, const std::string& name) const {
    t[name].push_back(std::chrono::duration<double, std::milli>(Clock::now() - wall).count());
    t["cpu." + name].push_back(cpu_ms() - cpu);
  }
};

int run(int argc, char** argv) {
  std::string scene_dir = SM_BENCH_DEFAULT_SCENE, json_path;
  int runs = 5, levels = 128, width = 320, height = 240, threads = 2;
  int census = 15, sw = 5, cost_shift = 2, occ = -1;
  std::vector<int> sw_table;
  bool no_opencv = false;
  CLI::App app{"Model speed (1 and N threads) vs OpenCV StereoSGBM / StereoBinarySGBM (1 thread), medians"};
  app.add_option("--scene", scene_dir, "scene folder with left.png/right.png (resized to WxH)")->capture_default_str();
  app.add_option("--runs", runs, "repetitions (median)")->check(sm::tools::int_in(1, 1000))->capture_default_str();
  app.add_option("--levels", levels, "disparity levels of every method (even, 4..254)")->capture_default_str();
  app.add_option("--width", width, "frame width")->check(sm::tools::int_in(16, 4096))->capture_default_str();
  app.add_option("--height", height, "frame height")->check(sm::tools::int_in(16, 4096))->capture_default_str();
  app.add_option("--census", census, "model census window (paper: 15)")->capture_default_str();
  app.add_option("--sw", sw, "model support-weight window (paper: 5)")->capture_default_str();
  // The three options below only widen the bit-exactness check (other arithmetic ranges,
  // weight sets including all-zero and all-4 windows); the speed figures use the defaults.
  app.add_option("--cost-shift", cost_shift, "model COST_SHIFT (paper: 2)")->capture_default_str();
  app.add_option("--sw-table", sw_table,
                 "model weight codes 0..3 by |dI| >> 3 (up to 32; the "
                 "rest 0; default: the register defaults)")
      ->delimiter(',');
  app.add_option("--occ", occ, "model occlusion penalty (default: the register default)")
      ->check(sm::tools::int_in(0, 255));
  app.add_option("--threads", threads, "threads of the model's second timing (the first is 1 thread)")
      ->check(sm::tools::int_in(1, 64))
      ->capture_default_str();
  app.add_option("--json", json_path, "write the medians as JSON");
  app.add_flag("--no-opencv", no_opencv, "time the model only");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::check_levels("--levels", levels);
  sm::tools::quiet_opencv();
  cv::setNumThreads(1);

  const sm::tools::Scene sc = sm::tools::load_scene(scene_dir);
  cv::Mat l = sc.left, r = sc.right;
  if (l.cols != width || l.rows != height) {
    cv::resize(sc.left, l, cv::Size(width, height), 0, 0, cv::INTER_AREA);
    cv::resize(sc.right, r, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  }
  const sm::Image8 li = sm::tools::to_image8(l), ri = sm::tools::to_image8(r);

  sm::HwConfig hw;  // paper configuration: CENSUS 15, SW 5
  hw.max_width = width;
  hw.max_height = height;
  hw.disp = levels;
  hw.census = census;
  hw.sw = sw;
  hw.cost_shift = cost_shift;
  hw.validate();
  if (sw_table.size() > 32) throw sm::tools::ToolError("--sw-table: at most 32 codes");
  for (int c : sw_table)
    if (c < 0 || c > 3) throw sm::tools::ToolError("--sw-table: codes are 0..3");
  const sm::Regs regs = [&] {
    sm::Regs g = sm::Regs::defaults(hw);
    g.width = width;
    g.height = height;
    if (!sw_table.empty()) {
      g.sw_table.fill(0);
      for (size_t k = 0; k < sw_table.size(); ++k) g.sw_table[k] = static_cast<uint8_t>(sw_table[k]);
    }
    if (occ >= 0) g.occ = static_cast<uint8_t>(occ);
    return g;
  }();
  const int nd16 = (levels + 15) / 16 * 16;  // OpenCV needs a multiple of 16
  auto sgbm = cv::StereoSGBM::create(0, nd16, 5, 8 * 25, 32 * 25, 1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM);
  auto bsgbm = cv::stereo::StereoBinarySGBM::create(0, nd16, 9, 100, 1000, 1, 0, 5, 400, 200);

  std::map<std::string, std::vector<double>> t;
  std::vector<std::string> stage_order;
  // Fingerprints of every intermediate (outside the timed runs, volumes kept).
  uint64_t h_raw = 0, h_agg = 0, h_dp = 0, h_post = 0;
  {
    const sm::PipelineResult res = sm::run_pipeline(li, ri, hw, regs, true);
    h_raw = fnv(res.raw.v);
    h_agg = fnv(res.agg.v);
    h_dp = fnv(res.dp.px);
    h_post = fnv(res.post.px);
    // run_pipeline streams rows through the stage kernels; the whole-frame stage
    // functions (what the RTL block tests compare against), composed in the same order
    // by sm::run_frame_stages, must give the same bits, with one thread and with N.
    for (int n : {1, threads}) {
      const sm::PipelineResult st = sm::run_frame_stages(li, ri, hw, regs, n);
      if (!(st.raw == res.raw) || !(st.agg == res.agg) || st.dp != res.dp || st.post != res.post)
        throw sm::tools::ToolError(fmt::format("run_pipeline and the stage functions ({} threads) differ", n));
    }
  }
  cv::Mat d;
  for (int k = 0; k < runs; ++k) {
    Lap lap;
    const sm::PipelineResult res = sm::run_pipeline(li, ri, hw, regs, false);
    lap.to(t, "model");
    if (k == 0)
      for (const auto& [n, ms] : res.stage_ms) stage_order.push_back(n);
    if (fnv(res.dp.px) != h_dp || fnv(res.post.px) != h_post)
      throw sm::tools::ToolError("model output differs between runs");
    for (const auto& [n, ms] : res.stage_ms) t["model." + n].push_back(ms);
    lap = Lap{};
    const sm::PipelineResult rn = sm::run_pipeline(li, ri, hw, regs, false, threads);
    lap.to(t, "model_mt");
    if (fnv(rn.dp.px) != h_dp || fnv(rn.post.px) != h_post)
      throw sm::tools::ToolError(fmt::format("model output with {} threads differs from 1 thread", threads));
    for (const auto& [n, ms] : rn.stage_ms) t["model_mt." + n].push_back(ms);
    if (no_opencv) continue;
    lap = Lap{};
    sgbm->compute(l, r, d);
    lap.to(t, "sgbm");
    lap = Lap{};
    bsgbm->compute(l, r, d);
    lap.to(t, "binsgbm");
  }

  nlohmann::json js;
  js["scene"] = scene_dir;
  js["size"] = fmt::format("{}x{}", width, height);
  js["levels"] = levels;
  js["runs"] = runs;
  js["threads"] = threads;
  js["fingerprint_raw"] = fmt::format("{:016x}", h_raw);
  js["fingerprint_agg"] = fmt::format("{:016x}", h_agg);
  js["fingerprint_dp"] = fmt::format("{:016x}", h_dp);
  js["fingerprint_post"] = fmt::format("{:016x}", h_post);
  fmt::print("model speed: {} {}x{}, {} levels, median of {} runs (ms / frame), OpenCV on 1 thread\n", scene_dir, width,
             height, levels, runs);
  fmt::print(
      "| method | ms / frame | frames/s | time vs model (1 thread) | CPU ms / frame (all threads) | CPU time vs model "
      "(1 thread) |\n|---|---|---|---|---|---|\n");
  const double mc = median(t["cpu.model"]);
  const double m = median(t["model"]);
  for (const char* n : {"model", "model_mt", "sgbm", "binsgbm"}) {
    if (!t.count(n)) continue;
    const double v = median(t[n]);
    const std::string k = n;
    const std::string label = k == "model"      ? "reference model (run_pipeline), 1 thread"
                              : k == "model_mt" ? fmt::format("reference model (run_pipeline), {} threads", threads)
                              : k == "sgbm"     ? "OpenCV StereoSGBM (block 5)"
                                                : "OpenCV StereoBinarySGBM (census, block 9)";
    const double c = median(t[std::string("cpu.") + n]);
    fmt::print("| {} | {:.1f} | {:.2f} | {:.2f}x | {:.1f} | {:.2f}x |\n", label, v, 1000.0 / v, v / m, c, c / mc);
    js["ms"][n] = v;
    js["cpu_ms"][n] = c;
  }
  const double scaling = m / median(t["model_mt"]);
  js["scaling"] = scaling;
  const double overhead = median(t["cpu.model_mt"]) / mc;
  js["cpu_mt_vs_1"] = overhead;
  fmt::print("\nmodel {} threads vs 1 thread: {:.2f}x faster (wall); CPU time of all threads {:.2f}x one thread's\n",
             threads, scaling, overhead);
  if (t.count("sgbm")) {
    const double vs = m / median(t["sgbm"]);
    js["model_vs_sgbm"] = vs;
    const double vc = mc / median(t["cpu.sgbm"]);
    js["model_vs_sgbm_cpu"] = vc;
    fmt::print("model 1 thread / StereoSGBM time: {:.2f} wall, {:.2f} CPU (below 1: the model is faster)\n", vs, vc);
  }
  // With N threads the row-streamed stages (census .. evidence) sum their bands' times (thread
  // time, not wall); the others are wall times of stages that run in bands or serially.
  fmt::print(
      "\nmodel stages (median ms; {0} threads: census .. evidence summed over the bands, the others wall):\n| stage | "
      "ms "
      "| share | ms, {0} threads |\n|---|---|---|---|\n",
      threads);
  for (const auto& n : stage_order) {
    const double v = median(t["model." + n]), vn = median(t["model_mt." + n]);
    fmt::print("| {} | {:.2f} | {:.0f} % | {:.2f} |\n", n, v, 100.0 * v / m, vn);
    js["stage_ms"][n] = v;
    js["stage_ms_mt"][n] = vn;
  }
  fmt::print("\nfingerprints (FNV-1a): cost {:016x} aggregate {:016x} dp {:016x} post {:016x}\n", h_raw, h_agg, h_dp,
             h_post);
  if (!json_path.empty()) sm::tools::write_text_atomic(json_path, js.dump(2) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("bench_model_speed", run, argc, argv); }
