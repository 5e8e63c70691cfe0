#include "sm_speckle_table.hpp"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <vector>

#include "sm_speckle.hpp"

namespace sm::tools {

namespace {

constexpr int32_t kNone = -1;  // invalid pixel
constexpr int32_t kKeep = -2;  // labelled while the table was full

class LabelTable {
 public:
  LabelTable(int labels, int max_size)
      : parent_(static_cast<size_t>(labels)),
        rank_(parent_.size()),
        size_(parent_.size()),
        last_row_(parent_.size()),
        refs_(parent_.size()),
        cap_(max_size + 1) {
    for (int32_t l = 0; l < labels; ++l) free_.push_back(l);
  }

  int32_t find(int32_t l, SpeckleTableStats& st) const {
    int hops = 0;
    for (; parent_[at(l)] != l; ++hops) l = parent_[at(l)];
    st.longest_find = std::max(st.longest_find, hops);
    return l;
  }
  // A new region of one pixel on row y; kKeep when no label is free.
  int32_t start(int y, SpeckleTableStats& st) {
    if (free_.empty()) return kKeep;
    const int32_t n = free_.front();
    free_.pop_front();
    parent_[at(n)] = n;
    rank_[at(n)] = 0;
    size_[at(n)] = 0;
    refs_[at(n)] = 0;
    add_pixel(n, y);
    st.peak_labels = std::max(st.peak_labels, static_cast<int>(parent_.size() - free_.size()));
    return n;
  }
  // Roots a and b (a: the upper neighbour's) become one; returns the survivor.
  int32_t merge(int32_t a, int32_t b) {
    if (rank_[at(b)] > rank_[at(a)]) std::swap(a, b);
    if (rank_[at(a)] == rank_[at(b)]) ++rank_[at(a)];
    parent_[at(b)] = a;
    ++refs_[at(a)];
    size_[at(a)] = std::min(cap_, size_[at(a)] + size_[at(b)]);
    last_row_[at(a)] = std::max(last_row_[at(a)], last_row_[at(b)]);
    return a;
  }
  void add_pixel(int32_t r, int y) {
    size_[at(r)] = std::min(cap_, size_[at(r)] + 1);
    last_row_[at(r)] = y;
    ++refs_[at(r)];
  }
  void saturate(int32_t r) { size_[at(r)] = cap_; }
  bool kept(int32_t r, int newest, bool final_rows) const {
    return (!final_rows && last_row_[at(r)] >= newest - 1) || size_[at(r)] >= cap_;
  }
  // A decided pixel no longer holds label l; labels nothing holds go back to the FIFO.
  void release(int32_t l) {
    while (--refs_[at(l)] == 0) {
      free_.push_back(l);
      if (parent_[at(l)] == l) break;
      l = parent_[at(l)];
    }
  }

 private:
  static size_t at(int32_t l) { return static_cast<size_t>(l); }
  std::vector<int32_t> parent_, rank_, size_, last_row_, refs_;
  std::deque<int32_t> free_;
  int32_t cap_;
};

// The label of pixel (x, y) from its neighbours' labels (kNone: not joined).
int32_t label_pixel(LabelTable& t, int32_t up, int32_t left, int y, SpeckleTableStats& st) {
  const bool keep = up == kKeep || left == kKeep;
  const int32_t ru = up >= 0 ? t.find(up, st) : kNone, rl = left >= 0 ? t.find(left, st) : kNone;
  int32_t r = ru >= 0 ? ru : rl;
  if (ru >= 0 && rl >= 0 && ru != rl) r = t.merge(ru, rl);
  if (r < 0) return keep ? kKeep : t.start(y, st);
  t.add_pixel(r, y);
  if (keep) t.saturate(r);
  return r;
}

}  // namespace

cv::Mat speckle_keep_table(const cv::Mat& q4, int max_size, int max_diff, int delay_rows, int labels,
                           SpeckleTableStats* stats) {
  CV_Assert(q4.type() == CV_16S && delay_rows >= 0 && labels >= 1);
  const int w = q4.cols, h = q4.rows;
  LabelTable t(labels, max_size);
  SpeckleTableStats st;
  cv::Mat lab(h, w, CV_32S, cv::Scalar(kNone)), keep = cv::Mat::zeros(h, w, CV_8U);
  auto decide = [&](int x, int y, int newest, bool final_rows) {
    const int32_t l = lab.at<int32_t>(y, x);
    if (l == kNone) return;
    keep.at<uint8_t>(y, x) = l == kKeep || t.kept(t.find(l, st), newest, final_rows);
    if (l >= 0) t.release(l);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (q4.at<int16_t>(y, x) >= 0) {
        const Joins j = joins(q4, y, x, max_diff);
        const int32_t up = j.up ? lab.at<int32_t>(y - 1, x) : kNone;
        const int32_t left = j.left ? lab.at<int32_t>(y, x - 1) : kNone;
        lab.at<int32_t>(y, x) = label_pixel(t, up, left, y, st);
        st.keep_pixels += lab.at<int32_t>(y, x) == kKeep;
      }
      if (y - delay_rows >= 0 && y < h - 1) decide(x, y - delay_rows, y, false);
    }
  for (int y = std::max(0, h - 1 - delay_rows); y < h; ++y)
    for (int x = 0; x < w; ++x) decide(x, y, h - 1, true);
  if (stats) *stats = st;
  return keep;
}

}  // namespace sm::tools
