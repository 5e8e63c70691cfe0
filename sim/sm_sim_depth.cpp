// stereo_sim's calibrated camera and metric outputs (sm_sim_depth.hpp).
#include "sm_sim_depth.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "toolio/sm_io.hpp"
#include "toolio/sm_outputs.hpp"

namespace fs = std::filesystem;

namespace sm::simapp {

namespace {

// The --regs file sets the calibration or the active size itself (an unreadable file is
// left to the register plan's error).
bool regs_file_sets_calib(const std::string& path) {
  if (path.empty()) return false;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() && (j.contains("calib") || j.contains("width") || j.contains("height"));
}

// A --scene run without a calibration of its own: the scene's calib.json when it fits.
void use_scene_calib(SimOptions& opt, const HwConfig& hw, SimCamera& cam) {
  const bool scene_input = opt.left.empty() && opt.seq_dir.empty() && opt.video.empty();
  if (!scene_input || !opt.calib.empty()) return;
  const std::string path = (fs::path(opt.scene_dir) / "calib.json").string();
  if (!fs::exists(path)) {
    cam.note = fmt::format("the scene has no calib.json: rectifier at identity, no camera (--calib FILE sets one)");
    return;
  }
  if (regs_file_sets_calib(opt.regs_file)) {
    cam.note = fmt::format("{} not used: --regs {} sets the calibration or the size", path, opt.regs_file);
    return;
  }
  CalibFile c;
  try {
    c = load_calib(path);
  } catch (const std::exception& e) {
    fail(fmt::format("--scene {}: {}", opt.scene_dir, e.what()));
  }
  if (c.width != opt.width || c.height != opt.height) {
    cam.note = fmt::format("{} is for {}x{}, the active size is {}x{}: not used (rectifier at identity)", path, c.width,
                           c.height, opt.width, opt.height);
    return;
  }
  try {
    check_calib_fits(path, c, hw);
  } catch (const std::exception& e) {
    cam.note = fmt::format("{}: not used (rectifier at identity)", e.what());
    return;
  }
  opt.calib = path;
  cam.from_scene = true;
}

}  // namespace

SimCamera resolve_camera(SimOptions& opt, const HwConfig& hw) {
  SimCamera cam;
  use_scene_calib(opt, hw, cam);
  if (!opt.calib.empty()) {
    try {
      cam.camera = load_calib(opt.calib).camera;
    } catch (const std::exception& e) {
      fail(e.what());
    }
    cam.calib = opt.calib;
    cam.note = fmt::format("{}{} ({})", opt.calib, cam.from_scene ? ", the scene's" : "",
                           cam.camera ? "rectifier grids and camera" : "rectifier grids; no camera: no depth");
  }
  opt.depth.check(cam.camera, cam.calib);
  return cam;
}

void add_calibration_report(const SimCamera& cam, nlohmann::json& report) {
  nlohmann::json c;
  c["file"] = cam.calib.empty() ? nlohmann::json() : nlohmann::json(cam.calib);
  c["from_scene"] = cam.from_scene;
  c["camera"] = nlohmann::json();
  if (cam.camera)
    c["camera"] = {{"f_px", cam.camera->f_px},
                   {"cx", cam.camera->cx},
                   {"cy", cam.camera->cy},
                   {"baseline_m", cam.camera->baseline_m}};
  c["note"] = cam.note;
  report["calibration"] = c;
}

void write_depth_outputs(tools::OutputSet& outs, const SimOptions& opt, const SimCamera& cam, const cv::Mat& disp,
                         const Image8& rect_left) {
  if (!opt.depth.any() || !cam.camera) return;
  opt.depth.write(outs, disp, tools::to_mat(rect_left), *cam.camera);
}

}  // namespace sm::simapp
