// Running the project's command-line tools from tests: a file's bytes, and a command's
// exit code with its stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sm::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct CmdResult {
  int rc = -1;  // exit code, -1 if the command did not exit normally
  std::string out, err;
};

// `"exe" args` through the shell; stdout and stderr pass through stdout.txt and
// stderr.txt in `scratch` (an existing folder), overwritten by the next call.
inline CmdResult run_cmd(const std::string& exe, const std::string& args, const std::filesystem::path& scratch) {
  const std::filesystem::path o = scratch / "stdout.txt", e = scratch / "stderr.txt";
  const std::string cmd = "\"" + exe + "\" " + args + " > \"" + o.string() + "\" 2> \"" + e.string() + "\"";
  const int st = std::system(cmd.c_str());
  CmdResult r;
  r.rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = slurp(o);
  r.err = slurp(e);
  return r;
}

}  // namespace sm::test
