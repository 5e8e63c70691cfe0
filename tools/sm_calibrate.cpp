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
// larger line-buffer radius than the configured RECT_RADIUS. Options, inputs and outputs are checked before any work
// (docs/robustness.md); outputs are all-or-nothing (sm::tools::OutputSet): a failed run leaves no JSON, YAML or
// rectified image behind, also when interrupted (SIGINT/SIGTERM).
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
#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_outputs.hpp"
#include "pre.hpp"
#include "lower_case.hpp"

namespace fs = std::filesystem;

namespace {

using sm::tools::ToolError;

struct Pair {
  std::string left, right;
};

bool is_image_name(const fs::path& p) {
  const std::string ext = sm::lower_extension(p.string());
  return ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".bmp" || ext == ".pgm" || ext == ".tif" ||
         ext == ".tiff";
}

// "left05.jpg (no right05.jpg)" for a left* or right* image without its partner.
std::string unpaired_note(const Pair& p) {
  const bool left = !p.left.empty();
  const std::string name = fs::path(left ? p.left : p.right).filename().string();
  const std::string rest = name.substr(left ? 4 : 5);
  return fmt::format("{} (no {}{})", name, left ? "right" : "left", rest);
}

// A folder's left*/right* images, paired by the rest of the name (case-insensitive). An
// image without its partner is refused: the calibration would silently use fewer pairs.
std::vector<Pair> find_folder_pairs(const std::string& dir) {
  std::map<std::string, Pair> by_key;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file() || !is_image_name(e.path())) continue;
    const std::string l = sm::lower_case(e.path().filename().string());
    if (l.rfind("left", 0) == 0) by_key[l.substr(4)].left = e.path().string();
    if (l.rfind("right", 0) == 0) by_key[l.substr(5)].right = e.path().string();
  }
  std::vector<Pair> pairs;
  std::vector<std::string> unpaired;
  for (const auto& [key, p] : by_key) {
    if (!p.left.empty() && !p.right.empty())
      pairs.push_back(p);
    else
      unpaired.push_back(unpaired_note(p));
  }
  if (!unpaired.empty()) {
    const size_t shown = std::min<size_t>(unpaired.size(), 3);
    throw ToolError(fmt::format("{}: {} unpaired image{}: {}{} (left*/right* images pair by the rest of the name)", dir,
                                unpaired.size(), unpaired.size() > 1 ? "s" : "",
                                fmt::join(unpaired.begin(), unpaired.begin() + static_cast<long>(shown), ", "),
                                unpaired.size() > shown ? ", ..." : ""));
  }
  if (pairs.empty()) throw ToolError(fmt::format("{}: no left*/right* image pairs in the folder", dir));
  return pairs;
}

// The names of a list file: an OpenCV FileStorage "imagelist" sequence, or else one name a
// line (blank lines and # comments skipped).
std::vector<std::string> read_list_names(const std::string& input) {
  std::vector<std::string> names;
  try {
    cv::FileStorage fsr(input, cv::FileStorage::READ);
    if (fsr.isOpened()) {
      const cv::FileNode n = fsr["imagelist"];
      if (n.type() != cv::FileNode::SEQ) throw std::runtime_error(fmt::format("{}: no 'imagelist' sequence", input));
      for (const auto& it : n) names.push_back(static_cast<std::string>(it));
      return names;
    }
  } catch (const cv::Exception&) {
    // not a FileStorage file: a plain list
  }
  std::ifstream f(input);
  std::string line;
  while (std::getline(f, line)) {
    line.erase(0, line.find_first_not_of(" \t\r"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (!line.empty() && line[0] != '#') names.push_back(line);
  }
  return names;
}

// A list file's pairs (left, right, left, right, ...; relative paths relative to the
// list), every entry checked before any work (and without OpenCV's own warning lines).
std::vector<Pair> find_list_pairs(const std::string& input) {
  const std::vector<std::string> names = read_list_names(input);
  if (names.empty() || names.size() % 2)
    throw std::runtime_error(
        fmt::format("{}: the image list must hold left/right pairs ({} names)", input, names.size()));
  const fs::path base = fs::path(input).parent_path();
  auto full = [&](const std::string& n) { return fs::path(n).is_absolute() ? n : (base / n).string(); };
  std::vector<Pair> pairs;
  for (size_t i = 0; i < names.size(); i += 2) pairs.push_back({full(names[i]), full(names[i + 1])});
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& p = i % 2 ? pairs[i / 2].right : pairs[i / 2].left;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
      throw std::runtime_error(fmt::format("{}: entry {} '{}': {}", input, i + 1, names[i],
                                           fs::exists(p, ec) ? "not a regular file" : "no such file"));
  }
  return pairs;
}

// A folder of left*/right* images, or a list file (find_list_pairs).
std::vector<Pair> find_pairs(const std::string& input) {
  if (!fs::exists(input)) throw std::runtime_error(fmt::format("{}: no such file or folder", input));
  return fs::is_directory(input) ? find_folder_pairs(input) : find_list_pairs(input);
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

struct Options {
  std::string input, out_json = "calib.json", out_yaml = "calib.yaml", board_s = "9x6", save_dir;
  double square = 1.0, alpha = 0.0, check_vdisp = 0;
  int width = 0, height = 0, rect_radius = 0;
  cv::Size board;  // from board_s
};

void add_options(CLI::App& app, Options& o) {
  const sm::HwConfig hw_default;  // the IP's default build: option defaults come from it
  o.width = hw_default.max_width;
  o.height = hw_default.max_height;
  o.rect_radius = hw_default.rect_radius;
  app.add_option("input", o.input, "folder of left*/right* images or an image list file")->required();
  app.add_option("--board", o.board_s, "inner corners per row x per column")->capture_default_str();
  app.add_option("--square", o.square,
                 "chessboard square size in metres (the unit of T and of the baseline; the default 1 gives them "
                 "in squares, not metres)")
      ->capture_default_str();
  app.add_option("--width", o.width, "active image width of the IP")->capture_default_str();
  app.add_option("--height", o.height, "active image height of the IP")->capture_default_str();
  app.add_option("--rect-radius", o.rect_radius, "RECT_RADIUS the IP is built with")->capture_default_str();
  app.add_option("--alpha", o.alpha, "stereoRectify free scaling, 0..1 (0: valid pixels only, 1: all)")
      ->capture_default_str();
  app.add_option("-o,--out", o.out_json, "calibration JSON (registers)")->capture_default_str();
  app.add_option("--check-vdisp", o.check_vdisp,
                 "fail when the mean |vertical disparity| of the rectified corners exceeds this "
                 "(px; 0: no check)");
  app.add_option("--save-rectified", o.save_dir,
                 "folder to write the model-rectified pairs to (side by side, PNG; created if missing)");
  app.add_option("--yaml", o.out_yaml, "camera parameters (cv::FileStorage YAML)")->capture_default_str();
}

// The values CLI11 does not check (a bad one exits 2, as a parse error); sets o.board.
void check_options(Options& o) {
  char x = 0, extra = 0;
  if (std::sscanf(o.board_s.c_str(), "%d%c%d%c", &o.board.width, &x, &o.board.height, &extra) != 3 ||
      (x != 'x' && x != 'X') || o.board.width < 2 || o.board.height < 2)
    throw sm::tools::UsageError(fmt::format("--board '{}': expected <cols>x<rows>, e.g. 9x6", o.board_s));
  if (o.width < 16 || o.width > 4095 || o.height < 16 || o.height > 4095)
    throw sm::tools::UsageError(fmt::format("--width/--height {}x{} outside 16..4095", o.width, o.height));
  if (o.rect_radius < 1 || o.rect_radius > 31)
    throw sm::tools::UsageError(fmt::format("--rect-radius {} outside 1..31", o.rect_radius));
  if (!std::isfinite(o.square) || !(o.square > 0))
    throw sm::tools::UsageError(fmt::format("--square {}: must be finite and > 0 (metres)", o.square));
  if (!(o.alpha >= 0 && o.alpha <= 1)) throw sm::tools::UsageError(fmt::format("--alpha {}: outside 0..1", o.alpha));
  if (!std::isfinite(o.check_vdisp) || o.check_vdisp < 0)
    throw sm::tools::UsageError(fmt::format("--check-vdisp {}: must be finite and >= 0", o.check_vdisp));
}

// Every output before any work: the JSON and the YAML writable, not the same file and not
// one of the images or the list file, the --save-rectified folder (created when missing)
// able to take the images.
void check_outputs(const Options& o, const std::vector<Pair>& pairs) {
  sm::tools::PathList inputs = {{"INPUT", o.input}};
  for (const Pair& p : pairs) inputs.insert(inputs.end(), {{"image", p.left}, {"image", p.right}});
  sm::tools::check_outputs({{"-o", o.out_json}, {"--yaml", o.out_yaml}}, false, inputs);
  if (!o.save_dir.empty()) sm::tools::check_output_folder("--save-rectified", o.save_dir);
}

// The pairs whose board was found, with the corners at the IP's size.
struct Views {
  std::vector<std::vector<cv::Point3f>> obj;
  std::vector<std::vector<cv::Point2f>> pts_l, pts_r;
  std::vector<cv::Mat> small_l, small_r;  // the images at the IP size, for the check
  cv::Size src_size;
};

std::vector<cv::Point3f> board_points(const Options& o) {
  std::vector<cv::Point3f> pts;
  for (int i = 0; i < o.board.height; ++i)
    for (int j = 0; j < o.board.width; ++j)
      pts.emplace_back(static_cast<float>(j * o.square), static_cast<float>(i * o.square), 0.f);
  return pts;
}

// Adds one pair to `v` when the board is found in both images; false when it is not.
bool add_view(const Pair& p, const Options& o, Views& v) {
  const cv::Mat l = load_gray(p.left), r = load_gray(p.right);
  if (l.size() != r.size()) throw std::runtime_error(fmt::format("{}: size differs from {}", p.right, p.left));
  if (v.src_size.area() == 0) v.src_size = l.size();
  if (l.size() != v.src_size) throw std::runtime_error(fmt::format("{}: size differs from the first image", p.left));
  std::vector<cv::Point2f> cl, cr;
  if (!find_corners(l, o.board, 11, cl) || !find_corners(r, o.board, 11, cr)) return false;
  // Corners at the IP size (pixel centres map as in cv::resize).
  const float kx = static_cast<float>(o.width) / l.cols, ky = static_cast<float>(o.height) / l.rows;
  for (auto* c : {&cl, &cr})
    for (auto& q : *c) q = {(q.x + 0.5f) * kx - 0.5f, (q.y + 0.5f) * ky - 0.5f};
  v.obj.push_back(board_points(o));
  v.pts_l.push_back(cl);
  v.pts_r.push_back(cr);
  const cv::Size size(o.width, o.height);
  cv::Mat sl, sr;
  cv::resize(l, sl, size, 0, 0, cv::INTER_AREA);
  cv::resize(r, sr, size, 0, 0, cv::INTER_AREA);
  v.small_l.push_back(sl);
  v.small_r.push_back(sr);
  return true;
}

Views find_views(const std::vector<Pair>& pairs, const Options& o) {
  Views v;
  for (const auto& p : pairs) {
    const bool ok = add_view(p, o, v);
    fmt::print("{} / {}: {}\n", fs::path(p.left).filename().string(), fs::path(p.right).filename().string(),
               ok ? "board found" : "board NOT found, skipped");
  }
  if (v.obj.size() < 3)
    throw std::runtime_error(fmt::format("{}: the board was found in only {} pairs, need 3", o.input, v.obj.size()));
  return v;
}

// The calibration of both cameras and the rig, and the registers it gives.
struct Calibration {
  cv::Mat k1, d1, k2, d2, rot, tr, e, f, r1, r2, p1, p2, q;
  double rms_l = 0, rms_r = 0, rms = 0;
  int need_l = 0, need_r = 0;
  sm::CalibFile cal;
};

Calibration calibrate(const Views& v, const Options& o) {
  Calibration c;
  const cv::Size size(o.width, o.height);
  std::vector<cv::Mat> rv, tv;
  c.rms_l = cv::calibrateCamera(v.obj, v.pts_l, size, c.k1, c.d1, rv, tv);
  c.rms_r = cv::calibrateCamera(v.obj, v.pts_r, size, c.k2, c.d2, rv, tv);
  c.rms = cv::stereoCalibrate(v.obj, v.pts_l, v.pts_r, c.k1, c.d1, c.k2, c.d2, size, c.rot, c.tr, c.e, c.f,
                              cv::CALIB_USE_INTRINSIC_GUESS,
                              cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6));
  cv::stereoRectify(c.k1, c.d1, c.k2, c.d2, size, c.rot, c.tr, c.r1, c.r2, c.p1, c.p2, c.q, cv::CALIB_ZERO_DISPARITY,
                    o.alpha, size);
  c.cal.width = o.width;
  c.cal.height = o.height;
  c.cal.left = grid_for(c.k1, c.d1, c.r1, c.p1, o.width, o.height);
  c.cal.right = grid_for(c.k2, c.d2, c.r2, c.p2, o.width, o.height);
  c.need_l = sm::rect_radius_needed(c.cal.left, o.width, o.height);
  c.need_r = sm::rect_radius_needed(c.cal.right, o.width, o.height);
  c.cal.rect_radius_needed = std::max(c.need_l, c.need_r);
  c.cal.camera = rect_camera(c.p1, c.p2);
  return c;
}

void write_yaml(const std::string& path, const Calibration& c, const Views& v, const Options& o) {
  cv::FileStorage y(path, cv::FileStorage::WRITE);
  if (!y.isOpened()) throw std::runtime_error(fmt::format("{}: cannot open for writing", path));
  y << "image_width" << o.width << "image_height" << o.height << "source_width" << v.src_size.width << "source_height"
    << v.src_size.height << "board" << o.board << "square" << o.square << "pairs_used" << static_cast<int>(v.obj.size())
    << "rms_left" << c.rms_l << "rms_right" << c.rms_r << "rms_stereo" << c.rms << "K1" << c.k1 << "D1" << c.d1 << "K2"
    << c.k2 << "D2" << c.d2 << "R" << c.rot << "T" << c.tr << "E" << c.e << "F" << c.f << "R1" << c.r1 << "R2" << c.r2
    << "P1" << c.p1 << "P2" << c.p2 << "Q" << c.q << "rect_radius_needed" << c.cal.rect_radius_needed << "f_px"
    << c.cal.camera->f_px << "cx" << c.cal.camera->cx << "cy" << c.cal.camera->cy << "baseline_m"
    << c.cal.camera->baseline_m;
}

void print_calibration(const Calibration& c, size_t pairs, const Views& v, const Options& o) {
  fmt::print("pairs used {} of {}; RMS reprojection error: left {:.4f}, right {:.4f}, stereo {:.4f} px\n", v.obj.size(),
             pairs, c.rms_l, c.rms_r, c.rms);
  fmt::print("rectified left camera: f {:.2f} px, principal point ({:.2f}, {:.2f}), baseline {:.6g} {}\n",
             c.cal.camera->f_px, c.cal.camera->cx, c.cal.camera->cy, c.cal.camera->baseline_m,
             o.square == 1.0 ? "squares (give --square in metres for metres)" : "m");
  fmt::print("line-buffer radius needed: left {}, right {} (configured RECT_RADIUS {})\n", c.need_l, c.need_r,
             o.rect_radius);
}

// |vertical disparity| of the corners found again on the model-rectified pairs.
struct Vdisp {
  double sum = 0, max = 0;
  long n = 0;
  int pairs = 0;
  int radius = 0;  // the RECT_RADIUS the pairs were rectified at
  double mean() const { return n ? sum / static_cast<double>(n) : 0.0; }
};

// Adds the corners of one rectified pair; the detector may number a board from either
// end, so the corners are paired the consistent way.
void add_vdisp(const cv::Mat& rl, const cv::Mat& rr, cv::Size board, Vdisp& vd) {
  std::vector<cv::Point2f> cl, cr;
  if (!find_corners_small(rl, board, cl) || !find_corners_small(rr, board, cr)) return;
  auto mean_dy = [&](bool reverse) {
    double s = 0;
    for (size_t k = 0; k < cl.size(); ++k) s += std::fabs(cl[k].y - cr[reverse ? cr.size() - 1 - k : k].y);
    return s / static_cast<double>(cl.size());
  };
  const bool rev = mean_dy(true) < mean_dy(false);
  for (size_t k = 0; k < cl.size(); ++k) {
    const double dy = std::fabs(cl[k].y - cr[rev ? cr.size() - 1 - k : k].y);
    vd.sum += dy;
    vd.max = std::max(vd.max, dy);
    ++vd.n;
  }
  ++vd.pairs;
}

// Rectifies every pair with the model's rectify (bit-exact with the RTL), stages the
// --save-rectified images in `outs` and measures the vertical disparity.
Vdisp check_rectified(const Views& v, const Calibration& c, const Options& o, sm::tools::OutputSet& outs) {
  sm::HwConfig hw;
  hw.max_width = o.width;
  hw.max_height = o.height;
  hw.rect_radius = std::min(31, std::max(o.rect_radius, c.cal.rect_radius_needed));
  Vdisp vd;
  vd.radius = hw.rect_radius;
  for (size_t i = 0; i < v.small_l.size(); ++i) {
    using sm::tools::to_image8, sm::tools::to_mat;
    const cv::Mat rl = to_mat(sm::rectify(to_image8(v.small_l[i]), c.cal.left, true, hw));
    const cv::Mat rr = to_mat(sm::rectify(to_image8(v.small_r[i]), c.cal.right, true, hw));
    if (!o.save_dir.empty()) {
      cv::Mat both;
      cv::hconcat(rl, rr, both);
      const std::string path = (fs::path(o.save_dir) / fmt::format("rectified_{:02d}.png", i)).string();
      outs.write(
          path, [&](const std::string& tmp) { sm::tools::write_image_atomic(tmp, both); }, true);
    }
    add_vdisp(rl, rr, o.board, vd);
  }
  return vd;
}

void print_vdisp(const Vdisp& vd, const Calibration& c) {
  if (vd.n == 0) {
    fmt::print("vertical disparity check: the board was not found in any rectified pair\n");
    return;
  }
  fmt::print(
      "vertical disparity of chessboard corners on the model-rectified images (RECT_RADIUS {}): "
      "mean |dy| {:.3f} px, max {:.3f} px over {} corners in {} pairs\n",
      vd.radius, vd.mean(), vd.max, vd.n, vd.pairs);
  fmt::print("(the IP's RECT_RADIUS must be at least {} for this calibration)\n", c.cal.rect_radius_needed);
}

// The checks after the calibration: --check-vdisp and the configured radius.
void check_result(const Vdisp& vd, const Calibration& c, const Views& v, const Options& o) {
  if (o.check_vdisp > 0 && vd.n == 0)
    throw ToolError(fmt::format(
        "--check-vdisp {}: the board was found in none of the {} model-rectified pairs at {}x{}, so the vertical "
        "disparity cannot be measured; nothing written",
        o.check_vdisp, v.small_l.size(), o.width, o.height));
  if (o.check_vdisp > 0 && vd.mean() > o.check_vdisp)
    throw std::runtime_error(
        fmt::format("mean |vertical disparity| {:.3f} px over {} corners exceeds --check-vdisp {}; nothing written",
                    vd.mean(), vd.n, o.check_vdisp));
  if (c.cal.rect_radius_needed > o.rect_radius)
    throw std::runtime_error(
        fmt::format("the rig needs RECT_RADIUS >= {} but the IP is configured with {}; nothing written (rebuild the "
                    "IP with a larger RECT_RADIUS and pass --rect-radius, or try a larger --alpha)",
                    c.cal.rect_radius_needed, o.rect_radius));
}

int run(int argc, char** argv) {
  CLI::App app{"Stereo chessboard calibration -> sm_rectify grid registers"};
  Options o;
  add_options(app, o);
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  sm::tools::quiet_opencv();
  check_options(o);
  const auto pairs = find_pairs(o.input);
  check_outputs(o, pairs);

  const Views v = find_views(pairs, o);
  const Calibration c = calibrate(v, o);
  // Every output goes to a temporary first; nothing is renamed into place unless the
  // whole run succeeds.
  sm::tools::OutputSet outs;
  outs.write(o.out_yaml, [&](const std::string& tmp) { write_yaml(tmp, c, v, o); });
  outs.write(o.out_json, [&](const std::string& tmp) { sm::save_calib(tmp, c.cal); });
  print_calibration(c, pairs.size(), v, o);
  const Vdisp vd = check_rectified(v, c, o, outs);
  print_vdisp(vd, c);
  check_result(vd, c, v, o);
  outs.commit();
  fmt::print("wrote {} and {}{}\n", o.out_json, o.out_yaml,
             o.save_dir.empty() ? "" : fmt::format(", rectified pairs in {}", o.save_dir));
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_calibrate", run, argc, argv); }
