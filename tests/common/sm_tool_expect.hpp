// What the robustness tests of the command-line tools expect of a refused run
// (docs/robustness.md "The tools: input checks and exit codes").
#pragma once

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "sm_cmd.hpp"

namespace sm::test {

// Exit code `rc`, exactly one line on stderr: "<tool>: error: " followed by text holding `what`.
inline void expect_error(const CmdResult& r, int rc, const std::string& tool, const std::string& what) {
  INFO("stdout: " << r.out);
  INFO("stderr: " << r.err);
  CHECK(r.rc == rc);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.rfind(tool + ": error: ", 0) == 0);
  CHECK(r.err.find(what) != std::string::npos);
}

// The folder holds nothing (no output, no temporary, no folder), or does not exist.
inline void expect_empty(const std::filesystem::path& dir) {
  if (!std::filesystem::exists(dir)) return;
  for (const auto& e : std::filesystem::directory_iterator(dir)) FAIL("left behind: " << e.path());
}

}  // namespace sm::test
