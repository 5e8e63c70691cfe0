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

#include "toolio/sm_outputs.hpp"

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

// Every file the run writes (--disp-each's per-frame files aside), as (option, path).
tools::PathList run_outputs(const SimOptions& opt) {
  tools::PathList o;
  for (const char* f : {"disparity.png", "disparity_color.png", "panel.png", "report.json"})
    o.emplace_back("--out", opt.out_dir + "/" + f);
  o.insert(o.end(), {{"--disp-file", opt.disp_file},
                     {"--wave", opt.wave_path},
                     {"--depth-file", opt.depth.depth_file},
                     {"--cloud", opt.depth.cloud},
                     {"--cloud-view", opt.depth.cloud_view}});
  return o;
}

// Every file the run may read, as (option, path): an output must not replace one.
tools::PathList run_inputs(const SimOptions& opt) {
  tools::PathList in = {{"--left", opt.left},      {"--right", opt.right}, {"--video", opt.video},
                        {"--regs", opt.regs_file}, {"--calib", opt.calib}, {"--synth-json", opt.synth_json}};
  for (const std::string& e : opt.regs_at) in.emplace_back("--regs-at", e.substr(e.find('=') + 1));
  if (opt.left.empty() && opt.seq_dir.empty() && opt.video.empty())
    for (const char* f : {"left.png", "right.png", "gt.png", "nonocc.png", "scale.txt", "calib.json"})
      in.emplace_back("--scene", (fs::path(opt.scene_dir) / f).string());
  std::error_code ec;
  if (!opt.seq_dir.empty())
    for (const auto& e : fs::directory_iterator(opt.seq_dir, ec)) in.emplace_back("--sequence", e.path().string());
  return in;
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

void check_files(const SimOptions& opt) {
  check_input_files(opt);
  check_register_files(opt);
  if (!opt.synth_json.empty()) {
    check_readable_file("--synth-json", opt.synth_json);
    read_synthesis_total(opt.synth_json);
  }
  tools::check_outputs(run_outputs(opt), true, run_inputs(opt));
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
