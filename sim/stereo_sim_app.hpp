// stereo_sim in two parts, so that the large configuration-independent part (command
// line, inputs, reference-model check, report, images: ~25 s of compile time) is compiled
// once for every stereo_sim_* executable instead of once per configuration:
// - stereo_sim_app.cpp (library sm_stereo_sim_app): the program, run_stereo_sim(), which
//   runs its stages in order (sm_sim_options, sm_sim_regplan, sm_sim_inputs,
//   sm_sim_simulate (progress: sm_sim_progress), sm_sim_check, sm_sim_report, sm_sim_outputs,
//   sm_sim_depth, sm_sim_pictures);
// - stereo_sim.cpp (one object per configuration): the Verilated model's side, run() on
//   the Testbench / SimEngine of that model, and main().
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "sm_host.hpp"
#include "sm_sim.hpp"
#include "sm_types.hpp"

namespace sm::simapp {

// The Verilated model this executable links: its configuration and what it traces.
struct ModelInfo {
  HwConfig hw;
  bool wave_build = false;  // full-depth trace: --wave-scope works
  bool wave_vcd = true;     // formats it writes
  bool wave_fst = false;
  const char* traced = "";  // what it traces, for messages
  std::string default_scene;
  std::string synth_json;       // the synthesis report of this configuration in the build
  std::string synth_json_docs;  // ... and the committed one
};

// One run of the model as the command line asks for it.
struct RunRequest {
  FrameFeed feed;  // the frames, streamed from their source
  int width = 0, height = 0;
  CameraTiming timing;
  const Regs* regs0 = nullptr;  // written before the first frame
  const std::vector<HostOp>* host = nullptr;
  bool quiet = false;
  std::string wave_fmt;  // "vcd" or "fst": the model of that trace format runs
  bool list_scopes = false;
  std::vector<std::string> wave_scopes;  // full names (TOP.sm_top....)
  int wave_depth = 0;
  VcdWindow window;  // window.path: the wave file to write (empty: none)
};

struct RunResult {
  SimResult res;
  double wall = 0;  // seconds
  // The status and error registers read back over AXI4-Lite at the end: (index into
  // sm::regmap::registers(), word).
  std::vector<std::pair<size_t, uint32_t>> status;
};

// The model's side: runs `req`; false when it only listed the traced scopes.
using RunFn = std::function<bool(const RunRequest& req, RunResult& out)>;
// The signal names of a wave file this executable can read (sm::wave_signal_names).
using WaveNamesFn = std::function<std::vector<std::string>(const std::string& path)>;

// The program: options, register plan, inputs, simulation, check, report, pictures.
// Returns the exit code.
int run_stereo_sim(int argc, char** argv, const ModelInfo& info, const RunFn& run, const WaveNamesFn& wave_names);

// The stages' errors: one line "stereo_sim: error: <msg>", exit code 2.
[[noreturn]] inline void fail(const std::string& msg) { throw std::runtime_error(msg); }

// A file written under a temporary name and renamed when complete; a failed run leaves
// none behind.
struct PartFile {
  std::string path, final_path;
  bool done = false;
  ~PartFile() {
    if (!done && !path.empty()) {
      std::error_code ec;
      std::filesystem::remove(path, ec);
    }
  }
};

}  // namespace sm::simapp
