#include "sm_scenegen.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "calib_file.hpp"
#include "sm_io.hpp"

namespace sm::tools {

namespace {

// Platform-independent random numbers: raw mt19937_64 output only (the std::
// distributions are implementation-defined, and the scene must be the same bytes
// everywhere for a given seed).
class Rng {
 public:
  explicit Rng(uint64_t seed) : g_(seed) {}
  double uniform() { return static_cast<double>(g_() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  double gauss() {  // Box-Muller
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  uint64_t raw() { return g_(); }

 private:
  std::mt19937_64 g_;
};

uint64_t mix(uint64_t z) {  // splitmix64 finaliser
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Lattice value in [-1, 1] for integer lattice point (i, j) of one octave of one texture.
double lattice(uint64_t key, int64_t i, int64_t j) {
  const uint64_t h = mix(key ^ mix(static_cast<uint64_t>(i) * 0x100000001b3ULL ^ mix(static_cast<uint64_t>(j))));
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

// Bilinear value noise with lattice spacing `cell` pixels.
double value_noise(uint64_t key, double u, double v, double cell) {
  const double fu = u / cell, fv = v / cell;
  const double iu = std::floor(fu), iv = std::floor(fv);
  const double au = fu - iu, av = fv - iv;
  const auto i = static_cast<int64_t>(iu), j = static_cast<int64_t>(iv);
  const double a = lattice(key, i, j), b = lattice(key, i + 1, j);
  const double c = lattice(key, i, j + 1), d = lattice(key, i + 1, j + 1);
  return (a * (1 - au) + b * au) * (1 - av) + (c * (1 - au) + d * au) * av;
}

// Piecewise-constant blocks: sharp edges for the census transform to lock onto.
double blocks(uint64_t key, double u, double v, double cell) {
  return lattice(key, static_cast<int64_t>(std::floor(u / cell)), static_cast<int64_t>(std::floor(v / cell)));
}

enum class Shape { kPlane, kRect, kDisc };

struct Surface {
  Shape shape = Shape::kPlane;
  double a = 0, b = 0, c = 0;             // disparity d = a + b*x + c*y (left coordinates)
  double cx = 0, cy = 0, rx = 0, ry = 0;  // extent in left coordinates
  uint64_t key = 0;                       // texture
  double base = 128, block_amp = 40, block_cell = 16;

  bool covers(double x, double y) const {
    switch (shape) {
      case Shape::kPlane:
        return true;
      case Shape::kRect:
        return x >= cx - rx && x < cx + rx && y >= cy - ry && y < cy + ry;
      case Shape::kDisc: {
        const double u = (x - cx) / rx, v = (y - cy) / ry;
        return u * u + v * v <= 1.0;
      }
    }
    return false;
  }
  double disp(double x, double y) const { return a + b * x + c * y; }
  // Left-view x of the surface point that the right view sees at (xr, y): xr = xl - d(xl, y).
  double left_x(double xr, double y) const { return (xr + a + c * y) / (1.0 - b); }
  double texture(double u, double v) const {
    return base + block_amp * blocks(key ^ 1, u, v, block_cell) + 30.0 * value_noise(key ^ 2, u, v, 7.0) +
           22.0 * value_noise(key ^ 3, u, v, 3.0) + 14.0 * value_noise(key ^ 4, u, v, 1.5);
  }
};

struct Hit {
  int idx = -1;
  double xl = 0, d = 0;
};

// Nearest surface seen by the LEFT camera at (x, y).
Hit cast_left(const std::vector<Surface>& s, double x, double y) {
  Hit h;
  for (int i = 0; i < static_cast<int>(s.size()); ++i) {
    if (!s[i].covers(x, y)) continue;
    const double d = s[i].disp(x, y);
    if (h.idx < 0 || d > h.d) h = {i, x, d};
  }
  return h;
}

// Nearest surface seen by the rectified RIGHT camera at (xr, y).
Hit cast_right(const std::vector<Surface>& s, double xr, double y) {
  Hit h;
  for (int i = 0; i < static_cast<int>(s.size()); ++i) {
    const double xl = s[i].left_x(xr, y);
    if (!s[i].covers(xl, y)) continue;
    const double d = s[i].disp(xl, y);
    if (h.idx < 0 || d > h.d) h = {i, xl, d};
  }
  return h;
}

uint8_t to_pixel(double v, double gain, double offset, double noise, Rng& rng) {
  double o = v * gain + offset;
  if (noise > 0) o += noise * rng.gauss();
  return static_cast<uint8_t>(std::clamp(std::lround(o), 0L, 255L));
}

std::vector<Surface> build_surfaces(const SceneParams& p) {
  Rng rng(p.seed * 0x2545F4914F6CDD1DULL + 17);
  const double L = p.levels;
  std::vector<Surface> s;
  Surface bg;
  bg.a = p.bg_disp >= 0 ? p.bg_disp : std::max(1.0, 0.04 * L);
  const double sx = p.bg_slant_x > -1e8 ? p.bg_slant_x : 0.10 * L;
  const double sy = p.bg_slant_y > -1e8 ? p.bg_slant_y : 0.12 * L;
  bg.b = sx / p.width;
  bg.c = sy / p.height;
  bg.key = rng.raw();
  bg.base = rng.uniform(100, 150);
  s.push_back(bg);
  const double d_bg_max = bg.a + std::max(0.0, sx) + std::max(0.0, sy);
  const double d_lo = std::max(std::ceil(d_bg_max) + 2.0, 0.3 * L);
  const double d_hi = std::max(d_lo, 0.95 * (L - 1));
  for (int k = 0; k < p.objects; ++k) {
    Surface o;
    o.shape = rng.uniform() < 0.5 ? Shape::kRect : Shape::kDisc;
    // Spread the objects over the near range, one slot each, in depth order.
    const double t = p.objects > 1 ? (k + rng.uniform(0.0, 0.8)) / p.objects : rng.uniform();
    o.a = std::floor(d_lo + t * (d_hi - d_lo));
    o.rx = std::floor(rng.uniform(0.06, 0.13) * p.width) + 2;
    o.ry = std::floor(rng.uniform(0.08, 0.18) * p.height) + 2;
    // Keep the object inside the right view when the width allows it.
    const double lo = std::min(o.a + o.rx, p.width - o.rx), hi = p.width - o.rx;
    o.cx = std::floor(rng.uniform(lo, std::max(lo, hi)));
    o.cy = std::floor(rng.uniform(o.ry, std::max(o.ry, p.height - o.ry)));
    o.key = rng.raw();
    o.base = rng.uniform(60, 190);
    o.block_amp = rng.uniform(25, 50);
    o.block_cell = std::floor(rng.uniform(6, 20));
    s.push_back(o);
  }
  return s;
}

cv::Vec2d apply(const cv::Matx33d& h, double x, double y) {
  const cv::Vec3d q = h * cv::Vec3d(x, y, 1.0);
  return {q[0] / q[2], q[1] / q[2]};
}

}  // namespace

SyntheticScene render_scene(const SceneParams& p) {
  if (p.width < 16 || p.height < 16 || p.width > 4095 || p.height > 4095)
    throw std::invalid_argument(fmt::format("image size {}x{} outside 16..4095", p.width, p.height));
  if (p.levels < 2 || p.levels > 255) throw std::invalid_argument(fmt::format("levels {} outside 2..255", p.levels));
  if (p.objects < 0 || p.objects > 64) throw std::invalid_argument(fmt::format("objects {} outside 0..64", p.objects));
  if (p.noise < 0) throw std::invalid_argument("noise must be >= 0");
  const bool f_ok = std::isfinite(p.focal_px) && p.focal_px > 0, b_ok = std::isfinite(p.baseline_m) && p.baseline_m > 0;
  if ((p.focal_px != 0 || p.baseline_m != 0) && !(f_ok && b_ok))
    throw std::invalid_argument(
        fmt::format("focal length {} px and baseline {} m: give both, finite and > 0", p.focal_px, p.baseline_m));
  for (double v : {p.bg_disp, p.bg_slant_x, p.bg_slant_y, p.gain_l, p.offset_l, p.gain_r, p.offset_r, p.rot_deg,
                   p.vshift, p.noise})
    if (!std::isfinite(v)) throw std::invalid_argument("scene parameters must be finite numbers");
  const std::vector<Surface> surf = build_surfaces(p);
  if (std::fabs(surf[0].b) >= 0.5) throw std::invalid_argument("background slant too steep");

  SyntheticScene out;
  const int W = p.width, H = p.height;
  out.left.create(H, W, CV_8UC1);
  out.right.create(H, W, CV_8UC1);
  out.gt.create(H, W, CV_32F);
  out.nonocc.create(H, W, CV_8UC1);

  const double cxm = (W - 1) / 2.0, cym = (H - 1) / 2.0, th = p.rot_deg * 3.14159265358979323846 / 180.0;
  const bool warped = p.rot_deg != 0.0 || p.vshift != 0.0;
  if (warped) {
    const cv::Matx33d t1(1, 0, -cxm, 0, 1, -cym, 0, 0, 1);
    const cv::Matx33d r(std::cos(th), -std::sin(th), 0, std::sin(th), std::cos(th), 0, 0, 0, 1);
    const cv::Matx33d t2(1, 0, cxm, 0, 1, cym + p.vshift, 0, 0, 1);
    out.h_raw_from_rect = t2 * r * t1;
    out.h_rect_from_raw = out.h_raw_from_rect.inv();
  }

  Rng noise_l(p.seed ^ 0x6a09e667f3bcc908ULL), noise_r(p.seed ^ 0xbb67ae8584caa73bULL);
  out.min_disp = 1e9;
  out.max_disp = -1e9;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Hit hl = cast_left(surf, x, y);
      const Surface& sl = surf[hl.idx];
      out.left.at<uint8_t>(y, x) = to_pixel(sl.texture(x, y), p.gain_l, p.offset_l, p.noise, noise_l);
      out.gt.at<float>(y, x) = static_cast<float>(hl.d);
      out.min_disp = std::min(out.min_disp, hl.d);
      out.max_disp = std::max(out.max_disp, hl.d);
      // Visible in the right view: the right camera's ray through the same surface point
      // (continuous xr = x - d) hits this surface first and lands inside the raw image.
      const double xr = x - hl.d;
      bool vis = xr >= 0 && xr <= W - 1 && cast_right(surf, xr, y).idx == hl.idx;
      if (vis && warped) {
        const cv::Vec2d raw = apply(out.h_raw_from_rect, xr, y);
        vis = raw[0] >= 0 && raw[0] <= W - 1 && raw[1] >= 0 && raw[1] <= H - 1;
      }
      out.nonocc.at<uint8_t>(y, x) = vis ? 255 : 0;
    }
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      double xr = x, yr = y;
      if (warped) {
        const cv::Vec2d q = apply(out.h_rect_from_raw, x, y);
        xr = q[0];
        yr = q[1];
      }
      const Hit hr = cast_right(surf, xr, yr);
      out.right.at<uint8_t>(y, x) = to_pixel(surf[hr.idx].texture(hr.xl, yr), p.gain_r, p.offset_r, p.noise, noise_r);
    }
  if (out.max_disp > p.levels - 1)
    throw std::invalid_argument(
        fmt::format("scene disparity {:.2f} exceeds levels-1 = {}", out.max_disp, p.levels - 1));
  if (out.min_disp < 0) throw std::invalid_argument(fmt::format("negative scene disparity {:.2f}", out.min_disp));
  return out;
}

std::vector<PlacedObject> placed_objects(const SceneParams& p) {
  const std::vector<Surface> surf = build_surfaces(p);
  std::vector<PlacedObject> out;
  for (size_t i = 1; i < surf.size(); ++i) {
    const Surface& o = surf[i];
    out.push_back({o.shape == Shape::kDisc, o.cx, o.cy, o.rx, o.ry, static_cast<int>(o.a)});
  }
  return out;
}

void write_scene(const SyntheticScene& s, const SceneParams& p, const std::string& dir, bool with_nonocc) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw ToolError(fmt::format("{}: cannot create directory", dir));
  cv::Mat gt16;
  s.gt.convertTo(gt16, CV_16U, kGtScale);  // rounds to nearest; every gt >= 0
  const fs::path d(dir);
  write_image_atomic((d / "left.png").string(), s.left);
  write_image_atomic((d / "right.png").string(), s.right);
  write_image_atomic((d / "gt.png").string(), gt16);
  if (with_nonocc) write_image_atomic((d / "nonocc.png").string(), s.nonocc);
  write_text_atomic((d / "scale.txt").string(), fmt::format("{} {}\n", kGtScale, p.levels));
  auto mat = [](const cv::Matx33d& m) {
    nlohmann::json a = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) a.push_back({m(r, 0), m(r, 1), m(r, 2)});
    return a;
  };
  nlohmann::json j;
  j["generator"] = "sm_scene";
  j["width"] = p.width;
  j["height"] = p.height;
  j["levels"] = p.levels;
  j["seed"] = p.seed;
  j["objects"] = p.objects;
  j["gt_scale"] = kGtScale;
  j["disparity_range"] = {s.min_disp, s.max_disp};
  j["left"] = {{"gain", p.gain_l},
               {"offset", p.offset_l},
               {"H_raw_from_rect", mat(cv::Matx33d::eye())},
               {"H_rect_from_raw", mat(cv::Matx33d::eye())}};
  j["right"] = {{"gain", p.gain_r},
                {"offset", p.offset_r},
                {"rot_deg", p.rot_deg},
                {"vshift", p.vshift},
                {"H_raw_from_rect", mat(s.h_raw_from_rect)},
                {"H_rect_from_raw", mat(s.h_rect_from_raw)}};
  j["noise_sigma"] = p.noise;
  const std::optional<RectCamera> cam =
      p.focal_px > 0
          ? std::optional<RectCamera>(RectCamera{p.focal_px, (p.width - 1) / 2.0, (p.height - 1) / 2.0, p.baseline_m})
          : std::nullopt;
  if (cam) j["camera"] = {{"f_px", cam->f_px}, {"cx", cam->cx}, {"cy", cam->cy}, {"baseline_m", cam->baseline_m}};
  write_text_atomic((d / "camera.json").string(), j.dump(2) + "\n");

  // The same cameras as the rectifier's register contents (model/calib_file.hpp): grid
  // point (16 gx, 16 gy) of the rectified view holds its raw source position, Q.5.
  CalibFile c;
  c.width = p.width;
  c.height = p.height;
  c.left = RectGrid::identity(p.width, p.height);
  c.right = c.left;
  double radius = 0;
  for (int gy = 0; gy < c.right.gh; ++gy)
    for (int gx = 0; gx < c.right.gw; ++gx) {
      const cv::Vec2d raw = apply(s.h_raw_from_rect, gx * kGridStep, gy * kGridStep);
      const size_t i = static_cast<size_t>(gy) * c.right.gw + gx;
      c.right.sx[i] = static_cast<int16_t>(std::lround(raw[0] * (1 << kMapFrac)));
      c.right.sy[i] = static_cast<int16_t>(std::lround(raw[1] * (1 << kMapFrac)));
      radius = std::max(radius, std::fabs(raw[1] - gy * kGridStep));
    }
  c.rect_radius_needed = static_cast<int>(std::ceil(radius)) + 1;
  c.camera = cam;
  const std::string calib = (d / "calib.json").string(), tmp = (d / ".calib.json.tmp").string();
  try {
    save_calib(tmp, c);
  } catch (const std::exception& e) {
    fs::remove(tmp, ec);
    throw ToolError(e.what());
  }
  fs::rename(tmp, calib, ec);
  if (ec) throw ToolError(fmt::format("{}: cannot write file", calib));
}

}  // namespace sm::tools
