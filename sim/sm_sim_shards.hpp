// Frame-parallel stereo_sim runs (issue 41). Each frame's output depends only on its own
// pixels and registers, so the frames of a run can be simulated apart:
// - a shard (--frame-range A:B --out DIR) simulates frames A..B-1 from reset, written
//   with the registers in force at frame A, the --regs-at schedule after it as in the
//   whole run; its report.json holds global frame numbers and a "shard" entry;
// - --jobs N splits the run into N contiguous shards, runs each in its own process (this
//   executable again) and merges them;
// - --merge-shards DIR... --out DIR merges the shard folders of a whole run into one
//   output (the one merge, for --jobs and for tools/sm_farm.py): per-frame results
//   concatenated, the timing figures of the first shard (frames streamed back to back),
//   the status read back and the pictures of the last. All or nothing: a missing or
//   inconsistent shard is one error line and no merged output.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "sm_sim_inputs.hpp"
#include "sm_sim_options.hpp"
#include "sm_sim_regplan.hpp"

namespace sm::simapp {

// --jobs, --frame-range, --merge-shards.
void add_shard_options(CLI::App& app, ShardOptions& o);

// The shard options against each other and the rest; an exit code when they conflict.
std::optional<int> check_shard_options(SimOptions& opt);

// A shard: the plan cut to its frames (registers and what the host changed for them in
// the whole run's schedule), the source moved to its first frame.
void start_shard(const SimOptions& opt, const HwConfig& hw, RegisterPlan& plan, SimInput& in);

// report.json's "shard" entry: the frames it holds, the whole run's, the disparity file,
// the run's command line (the merge takes shards of one run only) and the status lines
// read back at its end.
void add_shard_info(const SimOptions& opt, const SimInput& in, const std::vector<std::string>& status_lines,
                    nlohmann::json& rep);

// The `shards` contiguous frame ranges of a run of `nframes` frames ("A:B", B exclusive).
std::vector<std::string> shard_ranges(size_t nframes, int shards);

// --jobs: the run's `nframes` frames in opt.shard.jobs shards, then merged into opt.out_dir.
int run_jobs(const SimOptions& opt, size_t nframes);

// Merges shard folders into `out_dir` (disparity file `disp_file`, empty: <out>/disparity
// with the shards' extension); `wall` > 0: the run's wall time. Returns the exit code of
// the merged run (0 bit-exact and on time, 1 not); throws when the shards do not make one
// whole run.
int merge_shards(const std::vector<std::string>& dirs, const std::string& out_dir, std::string disp_file, bool quiet,
                 double wall = 0);
int merge_shard_dirs(const std::vector<std::string>& dirs, const std::string& out_dir, bool quiet);

}  // namespace sm::simapp
