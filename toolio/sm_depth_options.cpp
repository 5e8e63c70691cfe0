#include "sm_depth_options.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>

#include "sm_depth.hpp"
#include "sm_io.hpp"
#include "sm_pictures.hpp"

namespace sm::tools {

void DepthOptions::add(CLI::App& app) {
  app.add_option("--depth-file", depth_file,
                 "depth in metres (needs --calib with a camera): .pfm = float (+inf = invalid), .png = 16-bit "
                 "millimetres (0 = invalid)");
  app.add_option("--cloud", cloud, "point cloud, binary PLY: x y z (m, left camera) + intensity, valid pixels only");
  app.add_option("--cloud-max-depth", cloud_max_depth, "leave points farther than this (m) out of the cloud (0: none)");
  app.add_option("--cloud-view", cloud_view, "bird's-eye view of the point cloud (PNG)");
}

void DepthOptions::check(const std::optional<RectCamera>& camera, const std::string& calib) const {
  if (!depth_file.empty() && !is_depth_file_name(depth_file))
    throw ToolError(fmt::format("{}: --depth-file must end in .pfm or .png", depth_file));
  if (!cloud.empty() && std::filesystem::path(cloud).extension() != ".ply")
    throw ToolError(fmt::format("{}: --cloud must end in .ply", cloud));
  if (!cloud_view.empty() && std::filesystem::path(cloud_view).extension() != ".png")
    throw ToolError(fmt::format("{}: --cloud-view must end in .png", cloud_view));
  if (!std::isfinite(cloud_max_depth) || cloud_max_depth < 0)
    throw ToolError(fmt::format("--cloud-max-depth {}: must be finite and >= 0 (metres)", cloud_max_depth));
  if (any() && calib.empty()) throw ToolError("--depth-file/--cloud/--cloud-view need --calib with a camera");
  if (any() && !camera)
    throw ToolError(fmt::format("{}: no 'camera' (focal length, baseline) for --depth-file/--cloud", calib));
  if (camera) check_camera(*camera, calib);
}

void DepthOptions::write(OutputSet& outs, const cv::Mat& disp_f, const cv::Mat& grey, const RectCamera& cam) const {
  if (!any()) return;
  const cv::Mat z = disparity_to_depth(disp_f, cam);
  if (!depth_file.empty()) outs.write(depth_file, [&](const std::string& t) { write_depth_file(t, z); });
  const auto pts = depth_to_cloud(z, grey, cam, cloud_max_depth > 0 ? cloud_max_depth : INFINITY);
  if (!cloud.empty()) outs.write(cloud, [&](const std::string& t) { write_ply(t, pts); });
  if (!cloud_view.empty())
    outs.write(cloud_view, [&](const std::string& t) {
      write_image_atomic(t, sm::tools::cloud_view(pts, {disp_f.cols, disp_f.rows}, cloud_max_depth));
    });
}

}  // namespace sm::tools
