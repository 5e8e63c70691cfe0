#include "calib_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

namespace sm {

namespace {

constexpr const char* kFormat = "sm_calib";
constexpr int kVersion = 1;

int pow2_at_least(int v) {
  int p = 4;  // sm_rectify keeps at least 2 bits per grid coordinate
  while (p < v) p <<= 1;
  return p;
}

nlohmann::json grid_json(const RectGrid& g) { return nlohmann::json{{"sx", g.sx}, {"sy", g.sy}}; }

// The first key of object `j` that is not in `known`, or "" when all are known.
std::string unknown_key(const nlohmann::json& j, const std::vector<std::string>& known) {
  for (const auto& [k, v] : j.items())
    if (std::find(known.begin(), known.end(), k) == known.end()) return k;
  return "";
}

// The "camera" object: every field a finite number, focal length and baseline > 0.
RectCamera load_camera(const nlohmann::json& j, const std::function<void(const std::string&)>& fail) {
  if (!j.is_object()) fail("'camera' is not an object");
  if (const std::string k = unknown_key(j, {"f_px", "cx", "cy", "baseline_m"}); !k.empty())
    fail(fmt::format("unknown key 'camera.{}'", k));
  auto num = [&](const char* key, bool positive) {
    if (!j.contains(key)) fail(fmt::format("missing key 'camera.{}'", key));
    if (!j[key].is_number()) fail(fmt::format("'camera.{}' is not a number", key));
    const double v = j[key].get<double>();
    if (!std::isfinite(v) || (positive && !(v > 0)))
      fail(fmt::format("'camera.{}' = {} must be {}", key, v, positive ? "finite and > 0" : "finite"));
    return v;
  };
  RectCamera c;
  c.f_px = num("f_px", true);
  c.cx = num("cx", false);
  c.cy = num("cy", false);
  c.baseline_m = num("baseline_m", true);
  return c;
}

}  // namespace

int grid_gwmax(int max_width) { return pow2_at_least(RectGrid::points_w(max_width)); }
int grid_ghmax(int max_height) { return pow2_at_least(RectGrid::points_h(max_height)); }

uint32_t grid_waddr(const HwConfig& hw, int bank, int gx, int gy) {
  const int gwmax = grid_gwmax(hw.max_width), ghmax = grid_ghmax(hw.max_height);
  return static_cast<uint32_t>(((bank & 1) * ghmax + gy) * gwmax + gx);
}

uint32_t grid_wdata(const RectGrid& g, int gx, int gy) {
  const size_t i = static_cast<size_t>(gy) * g.gw + gx;
  return (static_cast<uint32_t>(static_cast<uint16_t>(g.sy[i])) << 16) | static_cast<uint16_t>(g.sx[i]);
}

void save_calib(const std::string& path, const CalibFile& c) {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["width"] = c.width;
  j["height"] = c.height;
  j["grid_step"] = kGridStep;
  j["frac_bits"] = kMapFrac;
  j["grid_w"] = c.left.gw;
  j["grid_h"] = c.left.gh;
  j["rect_radius_needed"] = c.rect_radius_needed;
  j["left"] = grid_json(c.left);
  j["right"] = grid_json(c.right);
  if (c.camera)
    j["camera"] = {
        {"f_px", c.camera->f_px}, {"cx", c.camera->cx}, {"cy", c.camera->cy}, {"baseline_m", c.camera->baseline_m}};
  std::ofstream f(path);
  if (!f) throw std::runtime_error(fmt::format("{}: cannot open for writing", path));
  f << j.dump(1) << "\n";
  if (!f) throw std::runtime_error(fmt::format("{}: write failed", path));
}

CalibFile load_calib(const std::string& path) {
  auto fail = [&](const std::string& what) { throw std::runtime_error(fmt::format("{}: {}", path, what)); };
  std::ifstream f(path);
  if (!f) fail("cannot open calibration file");
  nlohmann::json j;
  try {
    f >> j;
  } catch (const nlohmann::json::exception& e) {
    fail(fmt::format("malformed JSON ({})", e.what()));
  }
  if (!j.is_object()) fail("not a JSON object");
  if (const std::string k = unknown_key(j, {"format", "version", "width", "height", "grid_step", "frac_bits", "grid_w",
                                            "grid_h", "rect_radius_needed", "left", "right", "camera"});
      !k.empty())
    fail(fmt::format("unknown key '{}'", k));
  auto get_int = [&](const char* key, int lo, int hi) {
    if (!j.contains(key)) fail(fmt::format("missing key '{}'", key));
    if (!j[key].is_number_integer()) fail(fmt::format("'{}' is not an integer", key));
    const long v = j[key].get<long>();
    if (v < lo || v > hi) fail(fmt::format("'{}' = {} outside {}..{}", key, v, lo, hi));
    return static_cast<int>(v);
  };
  if (!j.contains("format") || j["format"] != kFormat) fail(fmt::format("'format' is not \"{}\"", kFormat));
  if (get_int("version", 0, 1 << 30) != kVersion) fail(fmt::format("unsupported version"));
  CalibFile c;
  c.width = get_int("width", 16, 4095);
  c.height = get_int("height", 16, 4095);
  if (get_int("grid_step", 0, 1 << 30) != kGridStep) fail(fmt::format("'grid_step' must be {}", kGridStep));
  if (get_int("frac_bits", 0, 1 << 30) != kMapFrac) fail(fmt::format("'frac_bits' must be {}", kMapFrac));
  const int gw = RectGrid::points_w(c.width), gh = RectGrid::points_h(c.height);
  if (get_int("grid_w", 0, 1 << 30) != gw || get_int("grid_h", 0, 1 << 30) != gh)
    fail(fmt::format("grid size must be {}x{} for a {}x{} image", gw, gh, c.width, c.height));
  c.rect_radius_needed = get_int("rect_radius_needed", 0, 1 << 30);
  const size_t n = static_cast<size_t>(gw) * gh;
  auto load_grid = [&](const char* cam, RectGrid& g) {
    if (!j.contains(cam) || !j[cam].is_object()) fail(fmt::format("missing object '{}'", cam));
    if (const std::string k = unknown_key(j[cam], {"sx", "sy"}); !k.empty())
      fail(fmt::format("unknown key '{}.{}'", cam, k));
    g.gw = gw;
    g.gh = gh;
    for (const char* comp : {"sx", "sy"}) {
      const auto& a = j[cam].contains(comp) ? j[cam][comp] : nlohmann::json();
      if (!a.is_array()) fail(fmt::format("'{}.{}' missing or not an array", cam, comp));
      if (a.size() != n)
        fail(fmt::format("'{}.{}' has {} values, expected {} ({}x{})", cam, comp, a.size(), n, gw, gh));
      std::vector<int16_t>& dst = comp[1] == 'x' ? g.sx : g.sy;
      dst.resize(n);
      for (size_t i = 0; i < n; ++i) {
        if (!a[i].is_number_integer()) fail(fmt::format("'{}.{}'[{}] is not an integer", cam, comp, i));
        const long v = a[i].get<long>();
        if (v < -32768 || v > 32767) fail(fmt::format("'{}.{}'[{}] = {} outside int16", cam, comp, i, v));
        dst[i] = static_cast<int16_t>(v);
      }
    }
  };
  load_grid("left", c.left);
  load_grid("right", c.right);
  if (j.contains("camera")) c.camera = load_camera(j["camera"], fail);
  return c;
}

void check_calib_fits(const std::string& path, const CalibFile& c, const HwConfig& hw) {
  if (c.rect_radius_needed > hw.rect_radius)
    throw std::runtime_error(fmt::format("{}: 'rect_radius_needed' = {} exceeds the IP's RECT_RADIUS {}", path,
                                         c.rect_radius_needed, hw.rect_radius));
}

CalibFile load_fitting_calib(const std::string& path, const HwConfig& hw) {
  CalibFile c = load_calib(path);
  check_calib_fits(path, c, hw);
  return c;
}

}  // namespace sm
