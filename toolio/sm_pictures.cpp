#include "sm_pictures.hpp"

#include "sm_metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace sm::tools {

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

bool valid_disp(float d) { return std::isfinite(d) && d >= 0; }

// Text scale for a picture `rows` tall: legible at 48 rows, not huge at 480.
double text_scale(int rows) { return std::clamp(rows / 600.0, 0.3, 0.5); }

void put_text(cv::Mat& img, const std::string& s, cv::Point org, double scale, const cv::Scalar& c) {
  cv::putText(img, s, org, kFont, scale, c, 1, cv::LINE_AA);
}

// Round steps 1, 2, 5 x 10^k: the smallest with at most `n` intervals over span.
double nice_step(double span, int n) {
  const double raw = span / std::max(1, n);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string tick_text(double v, double step) {
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return fmt::format("{:.{}f}", v, decimals);
}

cv::Vec3b vec3b(const cv::Scalar& s) {
  return cv::Vec3b(static_cast<uint8_t>(s[0]), static_cast<uint8_t>(s[1]), static_cast<uint8_t>(s[2]));
}

uint8_t level(double v, ColourRange r) {
  const double t = (v - r.lo) / (r.hi - r.lo);
  return static_cast<uint8_t>(std::lround(std::clamp(t, 0.0, 1.0) * 255.0));
}

}  // namespace

ColourRange data_range(const cv::Mat& disp_f) {
  CV_Assert(disp_f.type() == CV_32FC1);
  double lo = INFINITY, hi = -INFINITY;
  for (auto it = disp_f.begin<float>(); it != disp_f.end<float>(); ++it)
    if (valid_disp(*it)) {
      lo = std::min(lo, static_cast<double>(*it));
      hi = std::max(hi, static_cast<double>(*it));
    }
  if (!(lo <= hi)) return {0, 1};
  return {lo, hi > lo ? hi : lo + 1};
}

cv::Mat colourise(const cv::Mat& disp_f, ColourRange r) {
  CV_Assert(disp_f.type() == CV_32FC1 && r.hi > r.lo);
  cv::Mat g(disp_f.size(), CV_8UC1), c;
  for (int y = 0; y < disp_f.rows; ++y)
    for (int x = 0; x < disp_f.cols; ++x) {
      const float d = disp_f.at<float>(y, x);
      g.at<uint8_t>(y, x) = valid_disp(d) ? level(d, r) : 0;
    }
  cv::applyColorMap(g, c, cv::COLORMAP_TURBO);
  const cv::Vec3b invalid = vec3b(kInvalidColour), no_match = vec3b(kNoMatchColour);
  for (int y = 0; y < disp_f.rows; ++y)
    for (int x = 0; x < disp_f.cols; ++x) {
      const float d = disp_f.at<float>(y, x);
      if (!valid_disp(d)) c.at<cv::Vec3b>(y, x) = d == kNoMatchDisp ? no_match : invalid;
    }
  return c;
}

cv::Mat colour_bar(ColourRange r, int height, const RectCamera* cam) {
  CV_Assert(r.hi > r.lo && height >= 16);
  const double s = text_scale(height);
  int base = 0;
  const int th = cv::getTextSize("0", kFont, s, 1, &base).height;
  const int left = cv::getTextSize("0000.0", kFont, s, 1, &base).width + 4, bar_w = 14;
  const int right = cam ? cv::getTextSize("000.00 m", kFont, s, 1, &base).width + 4 : 4;
  const int top = th + 4, legend = 2 * th + 10, bar_h = std::max(4, height - top - legend - th);
  cv::Mat img(height, left + bar_w + right, CV_8UC3, cv::Scalar(0, 0, 0));
  // the bar: row i shows disparity hi at the top down to lo at the bottom
  cv::Mat g(bar_h, 1, CV_8UC1), col;
  for (int i = 0; i < bar_h; ++i) g.at<uint8_t>(i, 0) = level(r.hi - (r.hi - r.lo) * i / (bar_h - 1.0), r);
  cv::applyColorMap(g, col, cv::COLORMAP_TURBO);
  cv::resize(col, img(cv::Rect(left, top, bar_w, bar_h)), cv::Size(bar_w, bar_h), 0, 0, cv::INTER_NEAREST);
  auto row_of = [&](double d) { return top + static_cast<int>(std::lround((r.hi - d) / (r.hi - r.lo) * (bar_h - 1))); };
  const cv::Scalar white(255, 255, 255);
  put_text(img, "disp", {2, th + 1}, s, white);
  // disparity ticks at a round step, labels at least 1.5 text heights apart (a short bar
  // keeps only a few)
  const double step = nice_step(r.hi - r.lo, std::max(1, bar_h / (3 * th)));
  int last_label = -1000;
  for (double d = std::ceil(r.lo / step) * step; d <= r.hi + 1e-9; d += step) {
    const int y = row_of(d);
    cv::line(img, {left - 3, y}, {left - 1, y}, white);
    if (std::abs(y - last_label) < 3 * th / 2) continue;
    last_label = y;
    put_text(img, tick_text(d, step), {1, std::clamp(y + th / 2, th, height - 1)}, s, white);
  }
  if (cam) {
    // depth ticks: round depths 1, 2, 5 x 10^k m whose disparity f B / Z is in range,
    // at least 1.5 text heights apart
    put_text(img, "depth", {left + bar_w + 2, th + 1}, s, white);
    const double fb = cam->f_px * cam->baseline_m;
    int last_y = -1000;
    for (int k = -3; k <= 4; ++k)
      for (double m : {1.0, 2.0, 5.0}) {
        const double z = m * std::pow(10.0, k), d = fb / z;
        if (d < r.lo || d > r.hi || d <= 0) continue;
        const int y = row_of(d);
        if (std::abs(y - last_y) < 3 * th / 2) continue;
        last_y = y;
        cv::line(img, {left + bar_w, y}, {left + bar_w + 2, y}, white);
        put_text(img, fmt::format("{:g} m", z), {left + bar_w + 4, std::clamp(y + th / 2, th, height - 1)}, s, white);
      }
  }
  int ly = height - legend + 2;
  for (const auto& [c, name] : {std::pair{kNoMatchColour, "hidden"}, std::pair{kInvalidColour, "invalid"}}) {
    cv::rectangle(img, cv::Rect(left, ly, bar_w, th + 2), c, cv::FILLED);
    put_text(img, name, {2, ly + th + 1}, s * 0.9, white);
    ly += th + 4;
  }
  return img;
}

cv::Mat disparity_picture(const cv::Mat& disp_f, ColourRange r, const RectCamera* cam) {
  cv::Mat out;
  cv::hconcat(colourise(disp_f, r), colour_bar(r, std::max(16, disp_f.rows), cam), out);
  return out;
}

cv::Mat with_legend(const cv::Mat& img, const std::vector<std::pair<cv::Scalar, std::string>>& entries) {
  const double s = text_scale(img.rows);
  int base = 0;
  const int th = cv::getTextSize("Ag", kFont, s, 1, &base).height;
  // entries flow left to right and wrap to new lines when the width runs out
  std::vector<cv::Point> at;
  int x = 2, y = 2;
  for (const auto& [c, name] : entries) {
    const int w = th + 4 + cv::getTextSize(name, kFont, s, 1, &base).width + 10;
    if (x > 2 && x + w > img.cols) {
      x = 2;
      y += th + 6;
    }
    at.emplace_back(x, y);
    x += w;
  }
  cv::Mat strip(y + th + 6, img.cols, CV_8UC3, cv::Scalar(0, 0, 0));
  for (size_t i = 0; i < entries.size(); ++i) {
    cv::rectangle(strip, cv::Rect(at[i].x, at[i].y, th + 1, th + 1), entries[i].first, cv::FILLED);
    cv::rectangle(strip, cv::Rect(at[i].x, at[i].y, th + 1, th + 1), cv::Scalar(128, 128, 128), 1);
    put_text(strip, entries[i].second, {at[i].x + th + 4, at[i].y + th}, s, cv::Scalar(255, 255, 255));
  }
  cv::Mat top = img.channels() == 3 ? img : cv::Mat();
  if (top.empty()) cv::cvtColor(img, top, cv::COLOR_GRAY2BGR);
  cv::Mat out;
  cv::vconcat(top, strip, out);
  return out;
}

cv::Mat error_map(const cv::Mat& est, const cv::Mat& gt, const cv::Mat& mask) {
  CV_Assert(est.type() == CV_32FC1 && gt.type() == CV_32FC1 && est.size() == gt.size());
  cv::Mat m(gt.size(), CV_8UC3, kNotScoredColour);
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      const float g = gt.at<float>(y, x);
      if (!(g > 0) || (!mask.empty() && mask.at<uint8_t>(y, x) == 0)) continue;
      const float e = est.at<float>(y, x);
      m.at<cv::Vec3b>(y, x) =
          vec3b(!valid_disp(e) ? kNoEstColour : (std::fabs(e - g) > 1.0f ? kBadColour : kGoodColour));
    }
  return m;
}

cv::Mat error_map_picture(const cv::Mat& est, const cv::Mat& gt, const cv::Mat& mask) {
  return with_legend(error_map(est, gt, mask), {{kGoodColour, "good (<= 1 px)"},
                                                {kBadColour, "bad (> 1 px)"},
                                                {kNoEstColour, "invalid"},
                                                {kNotScoredColour, "not scored"}});
}

cv::Mat draw_objects(const cv::Mat& bgr, const std::vector<Object>& objects, bool too_many, bool table_full) {
  CV_Assert(bgr.type() == CV_8UC3);
  cv::Mat img = bgr.clone();
  const double s = text_scale(img.rows);
  int base = 0;
  for (size_t i = 0; i < objects.size(); ++i) {
    const Object& o = objects[i];
    const cv::Rect box(cv::Point(o.x0, o.y0), cv::Point(o.x1 + 1, o.y1 + 1));
    cv::rectangle(img, box, cv::Scalar(0, 0, 0), 3);
    cv::rectangle(img, box, cv::Scalar(255, 255, 255), 1);
    const std::string id = fmt::format("#{}", i);
    const cv::Size ts = cv::getTextSize(id, kFont, s, 1, &base);
    const cv::Point org(std::clamp<int>(o.x0 + 2, 0, std::max(0, img.cols - ts.width)),
                        std::clamp<int>(o.y0 + ts.height + 2, ts.height, img.rows - 1));
    cv::rectangle(img, cv::Rect(org.x - 1, org.y - ts.height - 1, ts.width + 2, ts.height + 3), cv::Scalar(0, 0, 0),
                  cv::FILLED);
    put_text(img, id, org, s, cv::Scalar(255, 255, 255));
  }
  std::string flags = std::string(too_many ? "TOO-MANY " : "") + (table_full ? "TABLE-FULL" : "");
  if (!flags.empty()) {
    const cv::Size ts = cv::getTextSize(flags, kFont, s, 1, &base);
    cv::rectangle(img, cv::Rect(0, img.rows - ts.height - 6, ts.width + 4, ts.height + 6), cv::Scalar(0, 0, 160),
                  cv::FILLED);
    put_text(img, flags, {2, img.rows - 3}, s, cv::Scalar(255, 255, 255));
  }
  return img;
}

cv::Mat side_by_side(const std::vector<cv::Mat>& tiles) {
  int rows = 0;
  for (const auto& t : tiles) rows = std::max(rows, t.rows);
  std::vector<cv::Mat> padded;
  for (const auto& t : tiles) {
    cv::Mat c = t;
    if (c.channels() == 1) cv::cvtColor(t, c, cv::COLOR_GRAY2BGR);
    cv::copyMakeBorder(c, c, 0, rows - c.rows, 0, 0, cv::BORDER_CONSTANT, cv::Scalar(0, 0, 0));
    padded.push_back(c);
  }
  cv::Mat out;
  cv::hconcat(padded, out);
  return out;
}

cv::Mat labelled(const cv::Mat& img, const std::string& label) {
  cv::Mat t = img.clone();
  const double scale = std::max(0.3, t.cols / 800.0);
  int base = 0;
  const cv::Size ts = cv::getTextSize(label, kFont, scale, 1, &base);
  cv::rectangle(t, cv::Rect(0, 0, std::min(t.cols, ts.width + 4), std::min(t.rows, ts.height + base + 4)),
                cv::Scalar(0, 0, 0), cv::FILLED);
  put_text(t, label, cv::Point(2, ts.height + 2), scale, cv::Scalar(255, 255, 255));
  return t;
}

cv::Mat cloud_view(const std::vector<CloudPoint>& points, cv::Size size, double z_max) {
  CV_Assert(size.width >= 32 && size.height >= 32);
  cv::Mat img(size, CV_8UC3, cv::Scalar(60, 30, 0));
  if (z_max <= 0) {
    std::vector<float> z;
    z.reserve(points.size());
    for (const auto& p : points) z.push_back(p.z);
    if (!z.empty()) {
      const size_t k = std::min(z.size() - 1, z.size() * 99 / 100);
      std::nth_element(z.begin(), z.begin() + static_cast<long>(k), z.end());
      z_max = z[k];
    }
    if (!(z_max > 0)) z_max = 1;
  }
  // square metres: the same scale across and up; the camera at the bottom centre
  const double px_per_m = (size.height - 20) / z_max;
  const int cx = size.width / 2, cy = size.height - 10;
  auto to_px = [&](double x, double z) {
    return cv::Point(cx + static_cast<int>(std::lround(x * px_per_m)),
                     cy - static_cast<int>(std::lround(z * px_per_m)));
  };
  const double s = text_scale(size.height), step = nice_step(z_max, 5);
  const cv::Scalar grid(110, 80, 40), white(255, 255, 255);
  for (double z = step; z <= z_max + 1e-9; z += step) {
    const int y = to_px(0, z).y;
    cv::line(img, {0, y}, {size.width - 1, y}, grid);
    put_text(img, fmt::format("{:g} m", z), {2, y - 2}, s, white);
  }
  for (double x = step; x * px_per_m < size.width / 2.0; x += step)
    for (double sx : {-x, x}) cv::line(img, to_px(sx, 0), to_px(sx, z_max), grid);
  for (const auto& p : points) {
    if (!(p.z <= z_max)) continue;
    const cv::Point q = to_px(p.x, p.z);
    if (q.x < 0 || q.y < 0 || q.x >= size.width || q.y >= size.height) continue;
    img.at<cv::Vec3b>(q) = cv::Vec3b(p.grey, p.grey, p.grey);
  }
  cv::circle(img, {cx, cy}, 4, cv::Scalar(0, 0, 255), cv::FILLED);
  put_text(img, "camera", {cx + 8, cy + 4}, s * 0.9, white);
  put_text(img, "top view: X across, Z up", {2, size.height - 3}, s * 0.9, white);
  return img;
}

}  // namespace sm::tools
