// stereo_sim's report: the run's figures (cycles, frame period, latency, clocks, the 30
// frames/s budget), the check, every frame's registers and object packet, the status read
// back, accuracy against ground truth and the synthesis figures, as report.json and as
// the text on stdout.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "sm_sim_check.hpp"
#include "sm_sim_inputs.hpp"
#include "sm_sim_options.hpp"
#include "sm_sim_regplan.hpp"
#include "sm_sim_simulate.hpp"
#include "stereo_sim_app.hpp"
#include "toolio/sm_metrics.hpp"

namespace sm::simapp {

// Timing figures of the run, from the first frame's cycles and the camera.
struct FrameFigures {
  uint64_t frame_cycles = 0;  // sof in -> last pixel out
  uint64_t input_cycles = 0;  // sof in -> last pixel in: W*H + camera blanking
  uint64_t tail_cycles = 0;   // last pixel in -> out
  uint64_t latency = 0;       // sof in -> first pixel out
  uint64_t period = 0;        // steady-state frame period (0: one frame)
  uint64_t pixels = 0;
  uint64_t ip_cycles_per_frame = 0;
  uint64_t fifo_max = 0;  // input FIFO high-water mark
  double camera_clock = 0, core_hz = 0;
  double line_period = 0;  // aclk cycles
  double min_clock_30 = 0, min_core_camera = 0;
  bool fps_ok = false;
};

struct SimReport {
  nlohmann::json json;  // report.json
  FrameFigures fig;
  std::vector<std::string> status_lines;  // the status registers read back, one line each
  std::vector<ObjectPacket> packets;      // the RTL's object packets, decoded
};

// The last frame's invalid words by the rule that cleared them (report.json's `invalid`;
// a pixel may fail several), and that object as one line for the console.
nlohmann::json invalid_json(const tools::FailCounts& c);
std::string invalid_line(const nlohmann::json& invalid);

// `disp`: the last frame's disparity (float, tools::disp_to_float). Throws on a
// --synth-json that is not a synthesis report.
SimReport make_report(const SimOptions& opt, const ModelInfo& info, const SimInput& in, const RegisterPlan& plan,
                      const SimRun& run, const ModelCheck& check, const cv::Mat& disp);

// The objects of report.json's frame_results, each frame's packet and boxes, what the
// host changed for it (the serial report and the merged one).
void print_objects(const nlohmann::json& frame_results);

void print_report(const SimOptions& opt, const HwConfig& hw, const SimInput& in, const RegisterPlan& plan,
                  const SimRun& run, const ModelCheck& check, const SimReport& rep);

// 0 when bit-exact, well framed and every register write on time, else 1; 3 when these
// hold but --core-mhz asked for the 30 frames/s check and the verdict is NO.
int report_exit_code(const SimOptions& opt, const SimRun& run, const ModelCheck& check, const SimReport& rep);

}  // namespace sm::simapp
