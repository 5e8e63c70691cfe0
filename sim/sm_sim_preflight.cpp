// stereo_sim's checks before any work (sm_sim_preflight.hpp).
#include "sm_sim_preflight.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace sm::simapp {

namespace {

std::string what(const std::string& option, const std::string& path) {
  return option.empty() ? path : option + " " + path;
}

void check_folder(const std::string& option, const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) fail(fmt::format("{}: no such folder", what(option, dir)));
  if (!fs::is_directory(dir, ec)) fail(fmt::format("{}: not a folder", what(option, dir)));
}

// The file names the run writes besides --disp-file, and what they hold.
std::vector<std::pair<std::string, std::string>> fixed_outputs(const std::string& out) {
  return {{out + "/disparity.png", "the disparity picture"},
          {out + "/disparity_color.png", "the colour disparity picture"},
          {out + "/panel.png", "the panel"},
          {out + "/report.json", "the report"}};
}

void check_disp_file_clash(const SimOptions& opt) {
  std::error_code ec;
  const fs::path disp = fs::weakly_canonical(fs::absolute(opt.disp_file), ec);
  for (const auto& [path, role] : fixed_outputs(opt.out_dir)) {
    const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
    if (p == disp) fail(fmt::format("--disp-file {}: the same file as {} ({})", opt.disp_file, role, path));
  }
}

// The input the options name (one of them: CLI11 excludes the others).
void check_input_files(const SimOptions& opt) {
  if (!opt.left.empty()) check_readable_file("--left", opt.left);
  if (!opt.right.empty()) check_readable_file("--right", opt.right);
  if (!opt.left.empty() || !opt.right.empty()) return;
  if (!opt.seq_dir.empty()) return check_folder("--sequence", opt.seq_dir);
  if (!opt.video.empty()) return check_readable_file("--video", opt.video);
  check_folder("--scene", opt.scene_dir);
}

void check_register_files(const SimOptions& opt) {
  if (!opt.regs_file.empty()) check_readable_file("--regs", opt.regs_file);
  if (!opt.calib.empty()) check_readable_file("--calib", opt.calib);
  for (const std::string& e : opt.regs_at) {
    const size_t eq = e.find('=');
    if (eq != std::string::npos && eq + 1 < e.size()) check_readable_file("--regs-at", e.substr(eq + 1));
  }
}

}  // namespace

void check_readable_file(const std::string& option, const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(fmt::format("{}: no such file", what(option, path)));
  if (fs::is_directory(path, ec)) fail(fmt::format("{}: is a directory", what(option, path)));
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) fail(fmt::format("{}: cannot open for reading: {}", what(option, path), std::strerror(errno)));
  ::close(fd);
}

void check_writable_path(const std::string& option, const std::string& path) {
  fs::path dir = fs::absolute(path).parent_path();
  std::error_code ec;
  while (!dir.empty() && !fs::exists(dir, ec) && dir != dir.parent_path()) dir = dir.parent_path();
  if (!fs::is_directory(dir, ec))
    fail(fmt::format("{}: cannot create a file there: {} is not a folder", what(option, path), dir.string()));
  std::string probe = (dir / ".stereo_sim_probe_XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    fail(fmt::format("{}: cannot create a file in {}: {}", what(option, path), dir.string(), std::strerror(errno)));
  ::close(fd);
  ::unlink(probe.c_str());
}

void check_files(const SimOptions& opt) {
  check_input_files(opt);
  check_register_files(opt);
  if (!opt.synth_json.empty()) {
    check_readable_file("--synth-json", opt.synth_json);
    read_synthesis_total(opt.synth_json);
  }
  check_writable_path("--out", opt.out_dir + "/report.json");
  check_writable_path("--disp-file", opt.disp_file);
  check_disp_file_clash(opt);
  if (!opt.wave_path.empty()) check_writable_path("--wave", opt.wave_path);
}

json read_synthesis_total(const std::string& path) {
  std::ifstream f(path);
  if (!f) fail(fmt::format("{}: cannot open for reading", path));
  json s;
  try {
    s = json::parse(f);
  } catch (const json::exception& e) {
    std::string msg = e.what();
    if (const size_t b = msg.find("] "); msg.rfind("[json.", 0) == 0 && b != std::string::npos) msg = msg.substr(b + 2);
    fail(fmt::format("{}: not a synthesis report: {}", path, msg));
  }
  if (!s.is_object() || !s.contains("total")) fail(fmt::format("{}: not a synthesis report: no 'total'", path));
  const json& t = s["total"];
  if (!t.is_object()) fail(fmt::format("{}: 'total' must be an object, not {}", path, t.type_name()));
  for (const char* k : {"luts", "lutram", "srl", "ffs", "bram36", "dsp", "lut_levels"})
    if (t.contains(k) && !t[k].is_number())
      fail(fmt::format("{}: 'total.{}' must be a number, not {}", path, k, t[k].type_name()));
  return t;
}

}  // namespace sm::simapp
