// sm_calibrate: chessboard stereo calibration -> rectifier registers (docs/calibration.md).
//
// Finds the chessboard in every left/right pair, calibrates both cameras and the rig
// (OpenCV calibrateCamera + stereoCalibrate) at the IP's active image size, computes the
// rectification (stereoRectify) and its maps (initUndistortRectifyMap), samples them on
// the 16-pixel register grid and writes the calibration JSON (sm::CalibFile, with the
// rectified left camera for metric depth: focal length, principal point and baseline from
// P1/P2, in the unit of --square) plus a YAML file of the camera parameters. It then checks the result the way the
// hardware will compute it: both images are rectified by the model's rectify() (bit-exact with the RTL), the chessboard
// is found again, and the mean |vertical disparity| of the matched corners is reported. Fails when the rig needs a
// larger line-buffer radius than the configured RECT_RADIUS. Outputs are all-or-nothing (sm::tools::OutputSet): a
// failed run leaves no JSON, YAML or rectified image behind, also when interrupted (SIGINT/SIGTERM).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "calib_file.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_outputs.hpp"
#include "pre.hpp"
#include "lower_case.hpp"

namespace fs = std::filesystem;

namespace {

struct Pair {
  std::string left, right;
};

// A folder of left*/right* images (paired by the rest of the name), or a list file:
// an OpenCV FileStorage with an "imagelist" sequence (left, right, left, right, ...) or
// a text file of the same paths one per line. Relative paths are relative to the list.
std::vector<Pair> find_pairs(const std::string& input) {
  std::vector<Pair> pairs;
  if (!fs::exists(input)) throw std::runtime_error(fmt::format("{}: no such file or folder", input));
  if (fs::is_directory(input)) {
    std::map<std::string, Pair> by_key;
    for (const auto& e : fs::directory_iterator(input)) {
      if (!e.is_regular_file()) continue;
      const std::string name = e.path().filename().string(), l = sm::lower_case(name);
      const std::string ext = sm::lower_extension(e.path().string());
      if (ext != ".jpg" && ext != ".jpeg" && ext != ".png" && ext != ".bmp" && ext != ".pgm" && ext != ".tif" &&
          ext != ".tiff")
        continue;
      if (l.rfind("left", 0) == 0) by_key[l.substr(4)].left = e.path().string();
      if (l.rfind("right", 0) == 0) by_key[l.substr(5)].right = e.path().string();
    }
    for (const auto& [key, p] : by_key)
      if (!p.left.empty() && !p.right.empty()) pairs.push_back(p);
    if (pairs.empty()) throw std::runtime_error(fmt::format("{}: no left*/right* image pairs in the folder", input));
    return pairs;
  }
  std::vector<std::string> names;
  bool read = false;
  try {
    cv::FileStorage fsr(input, cv::FileStorage::READ);
    if (fsr.isOpened()) {
      const cv::FileNode n = fsr["imagelist"];
      if (n.type() != cv::FileNode::SEQ) throw std::runtime_error(fmt::format("{}: no 'imagelist' sequence", input));
      for (const auto& it : n) names.push_back(static_cast<std::string>(it));
      read = true;
    }
  } catch (const cv::Exception&) {
    read = false;  // not a FileStorage file: a plain list
  }
  if (!read) {
    std::ifstream f(input);
    std::string line;
    while (std::getline(f, line)) {
      line.erase(0, line.find_first_not_of(" \t\r"));
      line.erase(line.find_last_not_of(" \t\r") + 1);
      if (!line.empty() && line[0] != '#') names.push_back(line);
    }
  }
  if (names.empty() || names.size() % 2)
    throw std::runtime_error(
        fmt::format("{}: the image list must hold left/right pairs ({} names)", input, names.size()));
  const fs::path base = fs::path(input).parent_path();
  for (size_t i = 0; i < names.size(); i += 2) {
    auto full = [&](const std::string& n) { return fs::path(n).is_absolute() ? n : (base / n).string(); };
    pairs.push_back({full(names[i]), full(names[i + 1])});
  }
  // every entry checked before any work (and without OpenCV's own warning lines)
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& p = i % 2 ? pairs[i / 2].right : pairs[i / 2].left;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
      throw std::runtime_error(fmt::format("{}: entry {} '{}': {}", input, i + 1, names[i],
                                           fs::exists(p, ec) ? "not a regular file" : "no such file"));
  }
  return pairs;
}

cv::Mat load_gray(const std::string& path) { return sm::tools::read_image(path, cv::IMREAD_GRAYSCALE); }

// The rectified left camera of stereoRectify's projections: P1 = [f 0 cx 0; 0 f cy 0; ...],
// P2 = [f 0 cx' Tx*f; ...] with the baseline B = -Tx (the right camera to the right of
// the left one), in the unit of the object points (--square).
sm::RectCamera rect_camera(const cv::Mat& p1, const cv::Mat& p2) {
  sm::RectCamera c;
  c.f_px = p1.at<double>(0, 0);
  c.cx = p1.at<double>(0, 2);
  c.cy = p1.at<double>(1, 2);
  c.baseline_m = -p2.at<double>(0, 3) / p2.at<double>(0, 0);
  if (!std::isfinite(c.f_px) || !(c.f_px > 0) || !std::isfinite(c.baseline_m) || !(c.baseline_m > 0))
    throw std::runtime_error(
        fmt::format("rectified camera f {} px, baseline {}: not a horizontal rig with the right camera on the right",
                    c.f_px, c.baseline_m));
  return c;
}

bool find_corners(const cv::Mat& img, cv::Size board, int win, std::vector<cv::Point2f>& c) {
  if (!cv::findChessboardCorners(img, board, c, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return false;
  cv::cornerSubPix(img, c, cv::Size(win, win), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.01));
  return true;
}

// The detector often misses a board at the IP's small size: retry on a 2x upscale and
// map the corners back.
bool find_corners_small(const cv::Mat& img, cv::Size board, std::vector<cv::Point2f>& c) {
  if (find_corners(img, board, 5, c)) return true;
  cv::Mat big;
  cv::resize(img, big, img.size() * 2, 0, 0, cv::INTER_CUBIC);
  if (!find_corners(big, board, 9, c)) return false;
  for (auto& q : c) q = {(q.x + 0.5f) * 0.5f - 0.5f, (q.y + 0.5f) * 0.5f - 0.5f};
  return true;
}

sm::RectGrid grid_for(const cv::Mat& k, const cv::Mat& d, const cv::Mat& r, const cv::Mat& p, int w, int h) {
  const int mw = (sm::RectGrid::points_w(w) - 1) * sm::kGridStep + 1;
  const int mh = (sm::RectGrid::points_h(h) - 1) * sm::kGridStep + 1;
  cv::Mat mx, my;
  cv::initUndistortRectifyMap(k, d, r, p, cv::Size(mw, mh), CV_32FC1, mx, my);
  std::vector<float> vx(mx.begin<float>(), mx.end<float>()), vy(my.begin<float>(), my.end<float>());
  return sm::grid_from_maps(vx, vy, mw, mh, w, h);
}

int run(int argc, char** argv) {
  CLI::App app{"Stereo chessboard calibration -> sm_rectify grid registers"};
  std::string input, out_json = "calib.json", out_yaml = "calib.yaml", board_s = "9x6";
  double square = 1.0, alpha = 0.0;
  const sm::HwConfig hw_default;  // the IP's default build: option defaults come from it
  int width = hw_default.max_width, height = hw_default.max_height, rect_radius = hw_default.rect_radius;
  app.add_option("input", input, "folder of left*/right* images or an image list file")->required();
  app.add_option("--board", board_s, "inner corners per row x per column")->capture_default_str();
  app.add_option("--square", square,
                 "chessboard square size in metres (the unit of T and of the baseline; the default 1 gives them "
                 "in squares, not metres)")
      ->capture_default_str();
  app.add_option("--width", width, "active image width of the IP")->capture_default_str();
  app.add_option("--height", height, "active image height of the IP")->capture_default_str();
  app.add_option("--rect-radius", rect_radius, "RECT_RADIUS the IP is built with")->capture_default_str();
  app.add_option("--alpha", alpha, "stereoRectify free scaling, 0..1 (0: valid pixels only, 1: all)")
      ->capture_default_str();
  app.add_option("-o,--out", out_json, "calibration JSON (registers)")->capture_default_str();
  double check_vdisp = 0;
  app.add_option("--check-vdisp", check_vdisp,
                 "fail when the mean |vertical disparity| of the rectified corners exceeds this "
                 "(px; 0: no check)");
  std::string save_dir;
  app.add_option("--save-rectified", save_dir,
                 "folder to write the model-rectified pairs to (side by side, PNG; created if missing)");
  app.add_option("--yaml", out_yaml, "camera parameters (cv::FileStorage YAML)")->capture_default_str();
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();

  cv::Size board;
  {
    char x = 0, extra = 0;
    if (std::sscanf(board_s.c_str(), "%d%c%d%c", &board.width, &x, &board.height, &extra) != 3 ||
        (x != 'x' && x != 'X') || board.width < 2 || board.height < 2)
      throw std::runtime_error(fmt::format("--board '{}': expected <cols>x<rows>, e.g. 9x6", board_s));
  }
  if (width < 16 || width > 4095 || height < 16 || height > 4095)
    throw std::runtime_error(fmt::format("--width/--height {}x{} outside 16..4095", width, height));
  if (rect_radius < 1 || rect_radius > 31)
    throw std::runtime_error(fmt::format("--rect-radius {} outside 1..31", rect_radius));
  if (!std::isfinite(square) || !(square > 0))
    throw std::runtime_error(fmt::format("--square {}: must be finite and > 0 (metres)", square));
  if (!(alpha >= 0 && alpha <= 1)) throw std::runtime_error(fmt::format("--alpha {}: outside 0..1", alpha));
  if (!std::isfinite(check_vdisp) || check_vdisp < 0)
    throw std::runtime_error(fmt::format("--check-vdisp {}: must be finite and >= 0", check_vdisp));

  const auto pairs = find_pairs(input);
  const cv::Size size(width, height);
  std::vector<std::vector<cv::Point3f>> obj;
  std::vector<std::vector<cv::Point2f>> pts_l, pts_r;
  std::vector<cv::Mat> small_l, small_r;  // the images at the IP size, for the check
  std::vector<cv::Point3f> board_pts;
  for (int i = 0; i < board.height; ++i)
    for (int j = 0; j < board.width; ++j)
      board_pts.emplace_back(static_cast<float>(j * square), static_cast<float>(i * square), 0.f);
  cv::Size src_size;
  for (const auto& p : pairs) {
    const cv::Mat l = load_gray(p.left), r = load_gray(p.right);
    if (l.size() != r.size()) throw std::runtime_error(fmt::format("{}: size differs from {}", p.right, p.left));
    if (src_size.area() == 0) src_size = l.size();
    if (l.size() != src_size) throw std::runtime_error(fmt::format("{}: size differs from the first image", p.left));
    std::vector<cv::Point2f> cl, cr;
    const bool ok = find_corners(l, board, 11, cl) && find_corners(r, board, 11, cr);
    fmt::print("{} / {}: {}\n", fs::path(p.left).filename().string(), fs::path(p.right).filename().string(),
               ok ? "board found" : "board NOT found, skipped");
    if (!ok) continue;
    // Corners at the IP size (pixel centres map as in cv::resize).
    const float kx = static_cast<float>(width) / l.cols, ky = static_cast<float>(height) / l.rows;
    for (auto* c : {&cl, &cr})
      for (auto& q : *c) q = {(q.x + 0.5f) * kx - 0.5f, (q.y + 0.5f) * ky - 0.5f};
    obj.push_back(board_pts);
    pts_l.push_back(cl);
    pts_r.push_back(cr);
    cv::Mat sl, sr;
    cv::resize(l, sl, size, 0, 0, cv::INTER_AREA);
    cv::resize(r, sr, size, 0, 0, cv::INTER_AREA);
    small_l.push_back(sl);
    small_r.push_back(sr);
  }
  if (obj.size() < 3)
    throw std::runtime_error(fmt::format("{}: the board was found in only {} pairs, need 3", input, obj.size()));

  cv::Mat k1, d1, k2, d2, rot, tr, e, f;
  std::vector<cv::Mat> rv, tv;
  const double rms_l = cv::calibrateCamera(obj, pts_l, size, k1, d1, rv, tv);
  const double rms_r = cv::calibrateCamera(obj, pts_r, size, k2, d2, rv, tv);
  const double rms =
      cv::stereoCalibrate(obj, pts_l, pts_r, k1, d1, k2, d2, size, rot, tr, e, f, cv::CALIB_USE_INTRINSIC_GUESS,
                          cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6));
  cv::Mat r1, r2, p1, p2, q;
  cv::stereoRectify(k1, d1, k2, d2, size, rot, tr, r1, r2, p1, p2, q, cv::CALIB_ZERO_DISPARITY, alpha, size);

  sm::CalibFile cal;
  cal.width = width;
  cal.height = height;
  cal.left = grid_for(k1, d1, r1, p1, width, height);
  cal.right = grid_for(k2, d2, r2, p2, width, height);
  const int need_l = sm::rect_radius_needed(cal.left, width, height);
  const int need_r = sm::rect_radius_needed(cal.right, width, height);
  cal.rect_radius_needed = std::max(need_l, need_r);
  cal.camera = rect_camera(p1, p2);

  // Every output goes to a temporary first; nothing is renamed into place unless the
  // whole run succeeds.
  sm::tools::OutputSet outs;
  outs.write(out_yaml, [&](const std::string& tmp) {
    cv::FileStorage y(tmp, cv::FileStorage::WRITE);
    if (!y.isOpened()) throw std::runtime_error(fmt::format("{}: cannot open for writing", tmp));
    y << "image_width" << width << "image_height" << height << "source_width" << src_size.width << "source_height"
      << src_size.height << "board" << board << "square" << square << "pairs_used" << static_cast<int>(obj.size())
      << "rms_left" << rms_l << "rms_right" << rms_r << "rms_stereo" << rms << "K1" << k1 << "D1" << d1 << "K2" << k2
      << "D2" << d2 << "R" << rot << "T" << tr << "E" << e << "F" << f << "R1" << r1 << "R2" << r2 << "P1" << p1 << "P2"
      << p2 << "Q" << q << "rect_radius_needed" << cal.rect_radius_needed << "f_px" << cal.camera->f_px << "cx"
      << cal.camera->cx << "cy" << cal.camera->cy << "baseline_m" << cal.camera->baseline_m;
  });
  outs.write(out_json, [&](const std::string& tmp) { sm::save_calib(tmp, cal); });
  fmt::print("pairs used {} of {}; RMS reprojection error: left {:.4f}, right {:.4f}, stereo {:.4f} px\n", obj.size(),
             pairs.size(), rms_l, rms_r, rms);
  fmt::print("rectified left camera: f {:.2f} px, principal point ({:.2f}, {:.2f}), baseline {:.6g} {}\n",
             cal.camera->f_px, cal.camera->cx, cal.camera->cy, cal.camera->baseline_m,
             square == 1.0 ? "squares (give --square in metres for metres)" : "m");
  fmt::print("line-buffer radius needed: left {}, right {} (configured RECT_RADIUS {})\n", need_l, need_r, rect_radius);

  // Check with the model's rectify at the configured radius (bit-exact with the RTL).
  sm::HwConfig hw;
  hw.max_width = width;
  hw.max_height = height;
  hw.rect_radius = std::min(31, std::max(rect_radius, cal.rect_radius_needed));
  double sum_dy = 0, max_dy = 0;
  long n_dy = 0;
  int n_pairs = 0;
  for (size_t i = 0; i < small_l.size(); ++i) {
    using sm::tools::to_image8, sm::tools::to_mat;
    const cv::Mat rl = to_mat(sm::rectify(to_image8(small_l[i]), cal.left, true, hw));
    const cv::Mat rr = to_mat(sm::rectify(to_image8(small_r[i]), cal.right, true, hw));
    if (!save_dir.empty()) {
      cv::Mat both;
      cv::hconcat(rl, rr, both);
      const std::string path = (fs::path(save_dir) / fmt::format("rectified_{:02d}.png", i)).string();
      outs.write(
          path, [&](const std::string& tmp) { sm::tools::write_image_atomic(tmp, both); }, true);
    }
    std::vector<cv::Point2f> cl, cr;
    if (!find_corners_small(rl, board, cl) || !find_corners_small(rr, board, cr)) continue;
    // the detector may number a board from either end; pair corners the consistent way
    auto mean_dy = [&](bool reverse) {
      double s = 0;
      for (size_t k = 0; k < cl.size(); ++k) s += std::fabs(cl[k].y - cr[reverse ? cr.size() - 1 - k : k].y);
      return s / static_cast<double>(cl.size());
    };
    const bool rev = mean_dy(true) < mean_dy(false);
    for (size_t k = 0; k < cl.size(); ++k) {
      const double dy = std::fabs(cl[k].y - cr[rev ? cr.size() - 1 - k : k].y);
      sum_dy += dy;
      max_dy = std::max(max_dy, dy);
      ++n_dy;
    }
    ++n_pairs;
  }
  if (n_dy == 0) {
    fmt::print("vertical disparity check: the board was not found in any rectified pair\n");
  } else {
    fmt::print(
        "vertical disparity of chessboard corners on the model-rectified images (RECT_RADIUS {}): "
        "mean |dy| {:.3f} px, max {:.3f} px over {} corners in {} pairs\n",
        hw.rect_radius, sum_dy / static_cast<double>(n_dy), max_dy, n_dy, n_pairs);
    fmt::print("(the IP's RECT_RADIUS must be at least {} for this calibration)\n", cal.rect_radius_needed);
  }

  const double mean_dy = n_dy ? sum_dy / static_cast<double>(n_dy) : 0.0;
  if (check_vdisp > 0 && (n_dy == 0 || mean_dy > check_vdisp))
    throw std::runtime_error(
        fmt::format("mean |vertical disparity| {:.3f} px over {} corners exceeds --check-vdisp {}; nothing written",
                    mean_dy, n_dy, check_vdisp));
  if (cal.rect_radius_needed > rect_radius)
    throw std::runtime_error(
        fmt::format("the rig needs RECT_RADIUS >= {} but the IP is configured with {}; nothing written (rebuild the "
                    "IP with a larger RECT_RADIUS and pass --rect-radius, or try a larger --alpha)",
                    cal.rect_radius_needed, rect_radius));
  outs.commit();
  fmt::print("wrote {} and {}{}\n", out_json, out_yaml,
             save_dir.empty() ? "" : fmt::format(", rectified pairs in {}", save_dir));
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_calibrate", run, argc, argv); }
