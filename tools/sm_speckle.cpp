#include "sm_speckle.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <utility>
#include <vector>

namespace sm::tools {

namespace {

// Union-find over the pixels in raster order; each root keeps its region's size and the
// lowest row it reaches.
struct Regions {
  std::vector<int32_t> parent, size, last_row;
  explicit Regions(size_t n) : parent(n), size(n, 1), last_row(n, 0) { std::iota(parent.begin(), parent.end(), 0); }
  int32_t find(int32_t p) {
    while (parent[static_cast<size_t>(p)] != p) {
      const int32_t up = parent[static_cast<size_t>(parent[static_cast<size_t>(p)])];
      parent[static_cast<size_t>(p)] = up;  // path halving
      p = up;
    }
    return p;
  }
  void join(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size[static_cast<size_t>(a)] < size[static_cast<size_t>(b)]) std::swap(a, b);
    parent[static_cast<size_t>(b)] = a;
    size[static_cast<size_t>(a)] += size[static_cast<size_t>(b)];
    last_row[static_cast<size_t>(a)] = std::max(last_row[static_cast<size_t>(a)], last_row[static_cast<size_t>(b)]);
  }
};

// Row y's verdicts once rows 0..newest are joined; a region reaching row newest is open
// unless newest is the frame's last row.
void decide_row(const cv::Mat& q4, Regions& g, int y, int newest, int max_size, cv::Mat& keep) {
  const int w = q4.cols;
  const bool final_rows = newest == q4.rows - 1;
  for (int x = 0; x < w; ++x) {
    if (q4.at<int16_t>(y, x) < 0) continue;
    const int32_t r = g.find(y * w + x);
    const bool open = !final_rows && g.last_row[static_cast<size_t>(r)] == newest;
    keep.at<uint8_t>(y, x) = open || g.size[static_cast<size_t>(r)] > max_size;
  }
}

// Joins pixel (x, y) to the neighbours of j.
void join_pixel(Regions& g, int w, int y, int x, Joins j) {
  g.last_row[static_cast<size_t>(y * w + x)] = y;
  if (j.left) g.join(y * w + x, y * w + x - 1);
  if (j.up) g.join(y * w + x, (y - 1) * w + x);
}

// How many distinct values of id(p) the valid pixels of rows y0..y1 have.
template <typename Id>
int distinct(const cv::Mat& q4, int y0, int y1, Id id) {
  std::vector<int32_t> v;
  for (int y = std::max(0, y0); y <= y1; ++y)
    for (int x = 0; x < q4.cols; ++x)
      if (q4.at<int16_t>(y, x) >= 0) v.push_back(id(y * q4.cols + x));
  std::sort(v.begin(), v.end());
  return static_cast<int>(std::unique(v.begin(), v.end()) - v.begin());
}

}  // namespace

Joins joins(const cv::Mat& q4, int y, int x, int max_diff) {
  auto near = [&](int y1, int x1) {
    const int a = q4.at<int16_t>(y, x), b = q4.at<int16_t>(y1, x1);
    return a >= 0 && b >= 0 && std::abs(a - b) <= max_diff;
  };
  return {x > 0 && near(y, x - 1), y > 0 && near(y - 1, x)};
}

cv::Mat speckle_keep(const cv::Mat& q4, int max_size, int max_diff, int delay_rows) {
  CV_Assert(q4.type() == CV_16S && delay_rows >= 0);
  const int w = q4.cols, h = q4.rows;
  Regions g(static_cast<size_t>(w) * static_cast<size_t>(h));
  cv::Mat keep = cv::Mat::zeros(h, w, CV_8U);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) join_pixel(g, w, y, x, joins(q4, y, x, max_diff));
    if (y - delay_rows >= 0 && y < h - 1) decide_row(q4, g, y - delay_rows, y, max_size, keep);
  }
  for (int y = std::max(0, h - 1 - delay_rows); y < h; ++y) decide_row(q4, g, y, h - 1, max_size, keep);
  return keep;
}

SpeckleHold speckle_hold(const cv::Mat& q4, int max_diff, int delay_rows) {
  CV_Assert(q4.type() == CV_16S && delay_rows >= 0);
  const int w = q4.cols, h = q4.rows;
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  Regions g(n);
  // A labeller's labels: a pixel that starts a region gets a new one, a pixel that joins
  // one region its label, a pixel that joins two the older (lower) of their labels, which
  // the merged region keeps; the pixels labelled before keep theirs.
  std::vector<int32_t> label_of_root(n, -1), given(n, -1);
  int32_t next = 0;
  SpeckleHold peak;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (q4.at<int16_t>(y, x) < 0) continue;
      const Joins j = joins(q4, y, x, max_diff);
      const int32_t ll = j.left ? label_of_root[static_cast<size_t>(g.find(y * w + x - 1))] : -1;
      const int32_t lu = j.up ? label_of_root[static_cast<size_t>(g.find((y - 1) * w + x))] : -1;
      const int32_t l = ll < 0 ? (lu < 0 ? next++ : lu) : (lu < 0 ? ll : std::min(ll, lu));
      join_pixel(g, w, y, x, j);
      given[static_cast<size_t>(y * w + x)] = l;
      label_of_root[static_cast<size_t>(g.find(y * w + x))] = l;
    }
    const int regions = distinct(q4, y - delay_rows, y, [&](int32_t p) { return g.find(p); });
    const int labels = distinct(q4, y - delay_rows, y, [&](int32_t p) { return given[static_cast<size_t>(p)]; });
    peak.regions = std::max(peak.regions, regions);
    peak.labels = std::max(peak.labels, labels);
  }
  return peak;
}

}  // namespace sm::tools
