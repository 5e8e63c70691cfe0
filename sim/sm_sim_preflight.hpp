// stereo_sim's checks before any work: every file it reads is there and readable, every
// folder it writes to can take a file, the output names do not clash, the synthesis
// report has the fields the report reads. Each throws one line naming the file or the
// option and the reason (fail()).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "sm_sim_options.hpp"
#include "stereo_sim_app.hpp"

namespace sm::simapp {

// `path` is a regular file this process can open: else "<option> <path>: no such file",
// "... is a directory", "... cannot open for reading: <reason>".
void check_readable_file(const std::string& option, const std::string& path);

// The input files and folders the options name, the register files (--regs, --calib,
// --regs-at), the synthesis report; every output (tools::check_outputs: the --out
// folder's files, --disp-file, the wave file, the depth outputs) can be written, no two
// are the same file and none is one of the run's inputs.
void check_files(const SimOptions& opt);

// The synthesis report at `path`: its "total" object, with the figures the report prints
// numbers. Throws "<path>: <reason>" (the key named) otherwise.
nlohmann::json read_synthesis_total(const std::string& path);

}  // namespace sm::simapp
