// Running stereo_sim from the system tests (test_sim_host, test_sim_inputs): one run into
// a fresh output folder, with its exit code, stdout, stderr and report.json.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "sm_cmd.hpp"

namespace sm::test {

struct SimRun {
  int rc = -1;
  std::string out, err;
  nlohmann::json report;  // null when the run wrote no report.json
  std::filesystem::path dir;
};

// `"exe" args -q --out <tmp>/<name>`, the output folder removed first; stdout and stderr
// pass through files in `tmp` (created when missing).
inline SimRun run_sim(const std::string& exe, const std::filesystem::path& tmp, const std::string& name,
                      const std::string& args) {
  std::filesystem::create_directories(tmp);
  SimRun r;
  r.dir = tmp / name;
  std::filesystem::remove_all(r.dir);
  const CmdResult c = run_cmd(exe, args + " -q --out \"" + r.dir.string() + "\"", tmp);
  r.rc = c.rc;
  r.out = c.out;
  r.err = c.err;
  if (std::filesystem::exists(r.dir / "report.json")) r.report = nlohmann::json::parse(slurp(r.dir / "report.json"));
  return r;
}

}  // namespace sm::test
