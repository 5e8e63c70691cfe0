// stereo_sim's first stage: the command line, parsed and checked into one SimOptions.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sm_types.hpp"
#include "toolio/sm_depth_options.hpp"
#include "stereo_sim_app.hpp"

namespace sm::simapp {

// Frame-parallel runs (sm_sim_shards.hpp): --jobs N, a shard's --frame-range A:B, and
// --merge-shards DIR...
struct ShardOptions {
  int jobs = 1;
  int list_shards = 0;        // --list-shards N: print the N shards' ranges and exit
  bool given = false;         // --frame-range: this process simulates frames first..end-1
  std::string range;          // --frame-range as given
  size_t first = 0, end = 0;  // end 0: to the last frame
  std::vector<std::string> merge;
  std::vector<std::string> argv;  // the command line, for the shards' processes
};

// Everything the command line asks for. Later stages read it, never the command line.
struct SimOptions {
  // inputs (one of: --left/--right, --sequence, --video, else --scene)
  std::string left, right, seq_dir, video, scene_dir;
  int frames = 0;  // 0: a sequence's or video's every frame, a pair or scene twice
  // active size; *_given: set on the command line (wins over a register file's)
  int width = 0, height = 0;
  bool width_given = false, height_given = false;
  // registers
  std::string regs_file, calib;
  std::vector<std::string> regs_at;  // FRAME=FILE, as given
  bool late_regs = false;            // --debug-late-regs (a deliberate fault for the tests)
  // Writes the register options given (--occ, --gain-l, ...) into r; out of range: a ToolError.
  std::function<void(const HwConfig&, Regs&)> apply_reg_options;
  // camera and clocks
  bool continuous = false;
  int hblank = 80, vblank = 22;
  double pixel_clock = 0, clock_mhz = 100.0, core_mhz = 0;
  bool core_mhz_given = false;  // asks for the 30 frames/s check: a NO is exit code 3
  // waves
  std::string wave_path;                 // --wave (empty: none)
  std::string wave_fmt;                  // "vcd" or "fst" (check_wave_options)
  std::vector<std::string> wave_scopes;  // full names after check_wave_options
  int wave_depth = 0;
  bool wave_list_scopes = false;
  std::string wave_list;  // --wave-list FILE
  int vcd_frame = 0, vcd_line = 0, vcd_lines = 4;
  uint64_t vcd_cycles = 0;
  // outputs
  std::string out_dir = "out";
  std::string disp_file;  // default <out>/disparity.pfm
  bool disp_each = false;
  tools::DepthOptions depth;  // --depth-file, --cloud, --cloud-max-depth, --cloud-view (sm_sim_depth)
  std::string synth_json;
  bool no_check = false, quiet = false;
  ShardOptions shard;
};

// Parses the command line into `opt`. Returns an exit code when the run ends here (help,
// a parse error, an inconsistent option), nothing when it goes on.
std::optional<int> parse_sim_options(int argc, char** argv, const ModelInfo& info, SimOptions& opt);

// The wave options against this executable's build: scopes in full form, the trace
// format from the file name; an old wave file of that name is removed. Throws on error.
void check_wave_options(const ModelInfo& info, SimOptions& opt);

// --disp-file must name a .pfm or .png. Throws on error.
void check_disp_file_option(const SimOptions& opt);

}  // namespace sm::simapp
