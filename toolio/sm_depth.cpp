#include "sm_depth.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "sm_io.hpp"
#include "sm_outputs.hpp"
#include "lower_case.hpp"

namespace sm::tools {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Little-endian bytes of a 32-bit word, whatever the host's byte order.
void put_le32(char* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

}  // namespace

void check_camera(const RectCamera& cam, const std::string& what) {
  if (!std::isfinite(cam.f_px) || !(cam.f_px > 0))
    throw ToolError(fmt::format("{}: focal length {} px must be finite and > 0", what, cam.f_px));
  if (!std::isfinite(cam.baseline_m) || !(cam.baseline_m > 0))
    throw ToolError(fmt::format("{}: baseline {} m must be finite and > 0", what, cam.baseline_m));
  if (!std::isfinite(cam.cx) || !std::isfinite(cam.cy))
    throw ToolError(fmt::format("{}: principal point ({}, {}) must be finite", what, cam.cx, cam.cy));
}

cv::Mat disparity_to_depth(const cv::Mat& disp_f, const RectCamera& cam) {
  CV_Assert(disp_f.type() == CV_32FC1);
  const double fb = cam.f_px * cam.baseline_m;
  cv::Mat z(disp_f.size(), CV_32F);
  for (int y = 0; y < disp_f.rows; ++y)
    for (int x = 0; x < disp_f.cols; ++x) {
      const float d = disp_f.at<float>(y, x);
      z.at<float>(y, x) = std::isfinite(d) && d > 0 ? static_cast<float>(fb / d) : kInf;
    }
  return z;
}

std::vector<CloudPoint> depth_to_cloud(const cv::Mat& depth, const cv::Mat& grey, const RectCamera& cam,
                                       double max_depth) {
  CV_Assert(depth.type() == CV_32FC1 && grey.type() == CV_8UC1 && grey.size() == depth.size());
  std::vector<CloudPoint> pts;
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x) {
      const double z = depth.at<float>(y, x);
      if (!std::isfinite(z) || !(z > 0) || z > max_depth) continue;
      pts.push_back({static_cast<float>((x - cam.cx) * z / cam.f_px), static_cast<float>((y - cam.cy) * z / cam.f_px),
                     static_cast<float>(z), grey.at<uint8_t>(y, x)});
    }
  return pts;
}

bool is_depth_file_name(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".pfm" || e == ".png";
}

void write_depth_file(const std::string& path, const cv::Mat& depth) {
  CV_Assert(depth.type() == CV_32FC1);
  const std::string ext = lower_extension(path);
  if (ext == ".pfm") {
    cv::Mat pfm = depth.clone();
    for (auto it = pfm.begin<float>(); it != pfm.end<float>(); ++it)
      if (!std::isfinite(*it) || !(*it > 0)) *it = kInf;
    write_image_atomic(path, pfm);
  } else if (ext == ".png") {
    cv::Mat mm(depth.size(), CV_16UC1);
    for (int y = 0; y < depth.rows; ++y)
      for (int x = 0; x < depth.cols; ++x) {
        const double v = std::round(static_cast<double>(depth.at<float>(y, x)) * 1000.0);
        mm.at<uint16_t>(y, x) = std::isfinite(v) && v >= 1 && v <= 65535 ? static_cast<uint16_t>(v) : 0;
      }
    write_image_atomic(path, mm);
  } else {
    throw ToolError(fmt::format("{}: unknown depth format '{}' (use .pfm or .png)", path, ext));
  }
}

cv::Mat read_depth_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".pfm" && ext != ".png")
    throw ToolError(fmt::format("{}: unknown depth format '{}' (use .pfm or .png)", path, ext));
  const cv::Mat m = read_image(path, cv::IMREAD_UNCHANGED);
  if (m.channels() != 1) throw ToolError(fmt::format("{}: expected a one-channel depth image", path));
  cv::Mat z;
  if (m.depth() == CV_32F) {
    z = m.clone();
  } else if (m.depth() == CV_16U) {
    m.convertTo(z, CV_32F, 1e-3);
    z.setTo(kInf, m == 0);
  } else {
    throw ToolError(fmt::format("{}: expected a float PFM or a 16-bit PNG depth", path));
  }
  for (auto it = z.begin<float>(); it != z.end<float>(); ++it)
    if (!std::isfinite(*it) || !(*it > 0)) *it = kInf;
  return z;
}

void write_ply(const std::string& path, const std::vector<CloudPoint>& points) {
  const std::string header = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment sm_stereo point cloud: metres, rectified left camera (X right, "
      "Y down, Z forward)\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar intensity\nend_header\n",
      points.size());
  constexpr size_t kRecord = 3 * 4 + 1;
  std::string body(points.size() * kRecord, '\0');
  static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "PLY float is IEEE-754 binary32");
  for (size_t i = 0; i < points.size(); ++i) {
    char* r = &body[i * kRecord];
    const float xyz[3] = {points[i].x, points[i].y, points[i].z};
    for (int k = 0; k < 3; ++k) {
      uint32_t bits = 0;
      std::memcpy(&bits, &xyz[k], 4);
      put_le32(r + 4 * k, bits);
    }
    r[12] = static_cast<char>(points[i].grey);
  }
  OutputSet out;  // a temporary renamed into place: never a truncated cloud under `path`
  out.write(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw ToolError(fmt::format("{}: cannot open for writing", tmp));
    f.write(header.data(), static_cast<std::streamsize>(header.size()));
    f.write(body.data(), static_cast<std::streamsize>(body.size()));
    f.close();
    if (!f) throw ToolError(fmt::format("{}: write failed", tmp));
  });
  out.commit();
}

}  // namespace sm::tools
