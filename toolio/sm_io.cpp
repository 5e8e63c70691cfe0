#include "sm_io.hpp"

#include "sm_cli.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sm_signal_cleanup.hpp"
#include "sm_cli.hpp"
#include "lower_case.hpp"

namespace fs = std::filesystem;

namespace sm::tools {

int guarded_main(const char* tool, int (*run)(int, char**), int argc, char** argv) {
  return run_guarded(tool, [&] { return run(argc, argv); });
}

std::optional<int> parse_args(CLI::App& app, int argc, char** argv) { return parse_cli(app, argc, argv); }

StderrMute::StderrMute() {
  std::fflush(stderr);
  saved_ = dup(2);
  const int nul = open("/dev/null", O_WRONLY);
  if (saved_ >= 0 && nul >= 0) dup2(nul, 2);
  if (nul >= 0) close(nul);
}

StderrMute::~StderrMute() {
  std::fflush(stderr);
  if (saved_ >= 0) {
    dup2(saved_, 2);
    close(saved_);
  }
}

void check_levels(const char* option, int levels, bool per_scene) {
  if (per_scene && levels == 0) return;
  if (levels < 4 || levels > 254 || levels % 2)
    throw UsageError(
        fmt::format("{} {}: must be {}even, 4..254", option, levels, per_scene ? "0 (per scene) or " : ""));
}

namespace {

std::string temp_name(const fs::path& p) {
  fs::path dir = p.parent_path();
  std::string name = fmt::format(".{}.tmp{}{}", p.stem().string(), getpid(), p.extension().string());
  return (dir / name).string();
}

}  // namespace

void check_input_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw ToolError(fmt::format("{}: no such file", path));
  if (fs::is_directory(st)) throw ToolError(fmt::format("{}: is a directory", path));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw ToolError(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
}

void quiet_opencv() { cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT); }

cv::Mat read_image(const std::string& path, int flags) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw ToolError(fmt::format("{}: no such file", path));
  if (fs::is_directory(path, ec)) throw ToolError(fmt::format("{}: is a directory", path));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw ToolError(fmt::format("{}: cannot open for reading", path));
  std::vector<uchar> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw ToolError(fmt::format("{}: empty file", path));
  cv::Mat m;
  {
    StderrMute mute;
    try {
      m = cv::imdecode(bytes, flags);
    } catch (const cv::Exception&) {
      m.release();
    }
  }
  if (m.empty()) throw ToolError(fmt::format("{}: not a readable image (unknown format or truncated)", path));
  return m;
}

cv::Mat load_grey_mat(const std::string& path) {
  cv::Mat m = read_image(path, cv::IMREAD_UNCHANGED);
  if (m.depth() != CV_8U) throw ToolError(fmt::format("{}: expected an 8-bit image", path));
  cv::Mat g;
  switch (m.channels()) {
    case 1:
      g = m;
      break;
    case 3:
      cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(m, g, cv::COLOR_BGRA2GRAY);
      break;
    default:
      throw ToolError(fmt::format("{}: unsupported channel count {}", path, m.channels()));
  }
  return g;
}

Image8 load_grey(const std::string& path) { return to_image8(load_grey_mat(path)); }

Image8 to_image8(const cv::Mat& grey) {
  CV_Assert(grey.type() == CV_8UC1);
  Image8 img(grey.cols, grey.rows);
  for (int y = 0; y < grey.rows; ++y) std::copy(grey.ptr<uint8_t>(y), grey.ptr<uint8_t>(y) + grey.cols, &img.at(0, y));
  return img;
}

cv::Mat to_mat(const Image8& img) {
  cv::Mat m(img.h, img.w, CV_8UC1);
  for (int y = 0; y < img.h; ++y) std::copy(&img.at(0, y), &img.at(0, y) + img.w, m.ptr<uint8_t>(y));
  return m;
}

void write_image_atomic(const std::string& path, const cv::Mat& img, const std::vector<int>& params) {
  const std::string tmp = temp_name(path);
  const RemoveOnSignal guard(tmp);
  bool ok = false;
  try {
    ok = cv::imwrite(tmp, img, params);
  } catch (const cv::Exception&) {
    ok = false;
  }
  std::error_code ec;
  if (ok) fs::rename(tmp, path, ec);
  if (!ok || ec) {
    fs::remove(tmp, ec);
    throw ToolError(fmt::format("{}: cannot write image", path));
  }
}

namespace {

// Writes through `body` to a temporary name beside `path`, then renames it: no partial file
// is ever left under `path`. Throws ToolError.
void write_stream_atomic(const std::string& path, const std::function<void(std::ostream&)>& body) {
  const std::string tmp = temp_name(path);
  const RemoveOnSignal guard(tmp);
  {
    std::ofstream f(tmp, std::ios::binary);
    body(f);
    f.close();
    if (!f) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw ToolError(fmt::format("{}: cannot write file", path));
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw ToolError(fmt::format("{}: cannot write file", path));
  }
}

}  // namespace

void write_text_atomic(const std::string& path, const std::string& text) {
  write_stream_atomic(path, [&](std::ostream& f) { f << text; });
}

void write_json_atomic(const std::string& path, const nlohmann::json& j) {
  // streamed, not dumped to a string first: a long run's report is megabytes
  write_stream_atomic(path, [&](std::ostream& f) { f << std::setw(2) << j << '\n'; });
}

cv::Mat disp_to_float(const DispImage& d) {
  cv::Mat f(d.h, d.w, CV_32F);
  for (int y = 0; y < d.h; ++y)
    for (int x = 0; x < d.w; ++x) {
      const DispPix p = d.at(x, y);
      f.at<float>(y, x) = disp_valid(p) ? static_cast<float>(disp_value(p)) : -1.0f;
    }
  return f;
}

cv::Mat disp_to_grey(const cv::Mat& disp_f, int levels) {
  CV_Assert(disp_f.type() == CV_32F);
  cv::Mat g(disp_f.size(), CV_8UC1);
  const double k = levels > 1 ? 254.0 / (levels - 1) : 0.0;
  for (int y = 0; y < disp_f.rows; ++y)
    for (int x = 0; x < disp_f.cols; ++x) {
      const float d = disp_f.at<float>(y, x);
      // clamped before rounding, so a disparity above levels - 1 is 255 (never an overflow)
      g.at<uint8_t>(y, x) =
          std::isfinite(d) && d >= 0 ? static_cast<uint8_t>(1 + std::lround(std::min(d * k, 254.0))) : 0;
    }
  return g;
}

cv::Mat disp_to_colour(const cv::Mat& disp_f, int levels) {
  const cv::Mat g = disp_to_grey(disp_f, levels);
  cv::Mat c;
  cv::applyColorMap(g, c, cv::COLORMAP_TURBO);
  c.setTo(cv::Scalar::all(0), g == 0);  // grey 0 is exactly the invalid pixels (NaN included)
  return c;
}

void write_disparity_file(const std::string& path, const cv::Mat& disp_f) {
  CV_Assert(disp_f.type() == CV_32FC1);
  const std::string ext = lower_extension(path);
  if (ext == ".png") {
    // KITTI-style: round(d * 16), 0 = invalid; saturate_cast clips at 65535.
    cv::Mat png(disp_f.size(), CV_16UC1);
    for (int y = 0; y < disp_f.rows; ++y)
      for (int x = 0; x < disp_f.cols; ++x) {
        const float d = disp_f.at<float>(y, x);
        png.at<uint16_t>(y, x) = d < 0 ? 0 : cv::saturate_cast<uint16_t>(std::lround(d * 16.0));
      }
    write_image_atomic(path, png);
  } else if (ext == ".pfm") {
    // Middlebury-style: float disparity, +infinity = invalid. OpenCV's PFM codec writes
    // the rows bottom to top as the format wants (and reads them back the same way).
    cv::Mat pfm = disp_f.clone();
    pfm.setTo(std::numeric_limits<float>::infinity(), disp_f < 0);
    write_image_atomic(path, pfm);
  } else {
    throw ToolError(fmt::format("{}: unknown disparity format '{}' (use .png or .pfm)", path, ext));
  }
}

cv::Mat read_disparity_file(const std::string& path, double png_scale) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".pfm")
    throw ToolError(fmt::format("{}: unknown disparity format '{}' (use .png or .pfm)", path, ext));
  if (!(png_scale > 0)) throw ToolError(fmt::format("{}: PNG disparity scale must be > 0", path));
  const cv::Mat m = read_image(path, cv::IMREAD_UNCHANGED);
  if (m.channels() != 1)
    throw ToolError(fmt::format("{}: expected a one-channel disparity image, found {} channels", path, m.channels()));
  cv::Mat f;
  if (m.depth() == CV_32F) {
    f = m.clone();
    for (int y = 0; y < f.rows; ++y)
      for (int x = 0; x < f.cols; ++x) {
        float& d = f.at<float>(y, x);
        if (!std::isfinite(d) || d < 0) d = -1.0f;
      }
  } else if (m.depth() == CV_16U || m.depth() == CV_8U) {
    m.convertTo(f, CV_32F, 1.0 / png_scale);
    f.setTo(-1.0f, m == 0);
  } else {
    throw ToolError(fmt::format("{}: expected a 16-bit PNG or a float PFM disparity", path));
  }
  return f;
}

bool is_scene_dir(const std::string& dir) {
  for (const char* f : {"left.png", "right.png", "gt.png", "scale.txt"})
    if (!fs::exists(fs::path(dir) / f)) return false;
  return true;
}

Scene load_scene(const std::string& dir) {
  Scene s;
  s.dir = dir;
  s.name = fs::path(dir).lexically_normal().filename().string();
  if (s.name.empty() || s.name == ".") s.name = fs::path(dir).lexically_normal().parent_path().filename().string();
  const fs::path d(dir);
  const std::string scale_path = (d / "scale.txt").string();
  {
    std::ifstream f(scale_path);
    if (!f) throw ToolError(fmt::format("{}: no such file", scale_path));
    if (!(f >> s.scale >> s.levels) || s.scale <= 0 || s.levels < 1)
      throw ToolError(fmt::format("{}: expected two numbers 'scale levels'", scale_path));
  }
  s.left = load_grey_mat((d / "left.png").string());
  s.right = load_grey_mat((d / "right.png").string());
  if (s.left.size() != s.right.size())
    throw ToolError(fmt::format("{}: left {}x{} and right {}x{} differ in size", dir, s.left.cols, s.left.rows,
                                s.right.cols, s.right.rows));
  const std::string gt_path = (d / "gt.png").string();
  cv::Mat raw = read_image(gt_path, cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
  if (raw.size() != s.left.size())
    throw ToolError(fmt::format("{}: size {}x{} differs from left.png", gt_path, raw.cols, raw.rows));
  raw.convertTo(s.gt, CV_32F, 1.0 / s.scale);
  const fs::path nonocc = d / "nonocc.png";
  if (fs::exists(nonocc)) {
    s.nonocc = read_image(nonocc.string(), cv::IMREAD_GRAYSCALE);
    if (s.nonocc.size() != s.left.size())
      throw ToolError(fmt::format("{}: size differs from left.png", nonocc.string()));
  }
  return s;
}

std::vector<std::string> list_scenes(const std::string& root) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw ToolError(fmt::format("{}: not a directory", root));
  if (is_scene_dir(root)) return {root};
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(root, ec))
    if (e.is_directory() && is_scene_dir(e.path().string())) out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

BadStats bad1(const cv::Mat& est_f, const cv::Mat& gt, const cv::Mat& mask) {
  CV_Assert(est_f.type() == CV_32F && gt.type() == CV_32F && est_f.size() == gt.size());
  CV_Assert(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == gt.size()));
  BadStats s;
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      const float g = gt.at<float>(y, x);
      if (!(g > 0) || (!mask.empty() && mask.at<uint8_t>(y, x) == 0)) continue;
      ++s.evaluated;
      const float e = est_f.at<float>(y, x);
      if (e < 0) {
        ++s.invalid;
        ++s.bad;
      } else if (std::fabs(e - g) > 1.0f) {
        ++s.bad;
      }
    }
  return s;
}

StreakStats streaks(const cv::Mat& est_f, const cv::Mat& gt, const cv::Mat& mask, int max_rows) {
  CV_Assert(est_f.type() == CV_32F && gt.type() == CV_32F && est_f.size() == gt.size());
  CV_Assert(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == gt.size()));
  CV_Assert(max_rows >= 1);
  auto evaluated = [&](int y, int x) {
    return gt.at<float>(y, x) > 0 && (mask.empty() || mask.at<uint8_t>(y, x) != 0);
  };
  StreakStats s;
  for (int y = 1; y + 1 < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      const float g = gt.at<float>(y, x);
      // near(j): row y + j is evaluated and its truth within 1 of this pixel's
      auto near = [&](int j) {
        return y + j >= 0 && y + j < gt.rows && evaluated(y + j, x) && std::fabs(gt.at<float>(y + j, x) - g) <= 1.0f;
      };
      if (!near(0) || !near(-1) || !near(1)) continue;
      ++s.smooth;
      const float e = est_f.at<float>(y, x);
      if (e < 0 || std::fabs(e - g) <= 1.0f) continue;  // invalid or not bad
      // differs(j): row y + j has a valid estimate more than 1 away from this pixel's
      auto differs = [&](int j) {
        const float o = est_f.at<float>(y + j, x);
        return o >= 0 && std::fabs(e - o) > 1.0f;
      };
      // rows y-du+1 .. y+dd-1 (at most max_rows) between two rows that disagree, truth smooth
      // from y-du to y+dd
      bool found = false;
      for (int du = 1; du <= max_rows && !found && near(-du); ++du) {
        if (!differs(-du)) continue;
        for (int dd = 1; du + dd <= max_rows + 1 && near(dd); ++dd)
          if (differs(dd)) {
            found = true;
            break;
          }
      }
      if (found) ++s.streak;
    }
  return s;
}

}  // namespace sm::tools
