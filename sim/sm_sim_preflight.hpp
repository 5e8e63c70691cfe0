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

// A file can be created at `path`: the nearest folder above it that exists is a folder
// in which a file can be created (tried with a temporary file, removed at once); missing
// folders below it are created when the outputs are written. Else "<option> <path>:
// <reason>".
void check_writable_path(const std::string& option, const std::string& path);

// The input files and folders the options name, the register files (--regs, --calib,
// --regs-at), the synthesis report; the output folder, --disp-file and the wave file can
// be written, --disp-file is not one of the run's other outputs.
void check_files(const SimOptions& opt);

// The synthesis report at `path`: its "total" object, with the figures the report prints
// numbers. Throws "<path>: <reason>" (the key named) otherwise.
nlohmann::json read_synthesis_total(const std::string& path);

}  // namespace sm::simapp
