#include "sm_output_bound.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <opencv2/ml.hpp>

#include "toolio/sm_metrics.hpp"
#include "confidence.hpp"

namespace sm::tools {
namespace {

constexpr int kSupportRadii[] = {1, 2, 7};  // windows of the output level: 3x3, 5x5, 15x15
constexpr int kTextureSides[] = {5, 15, 31};
constexpr double kGoalDensity = 85.0, kGoalBad1 = 5.0;  // issue 39's checked mode, 14-scene means

// Per pixel: how many pixels of the (2r + 1)^2 window hold a level within 1 of its own.
cv::Mat level_support(const DispImage& post, int r) {
  cv::Mat out(post.h, post.w, CV_32F);
  for (int y = 0; y < post.h; ++y)
    for (int x = 0; x < post.w; ++x) {
      const int d = static_cast<int>(disp_value(post.at(x, y)));
      int n = 0;
      for (int v = std::max(0, y - r); v <= std::min(post.h - 1, y + r); ++v)
        for (int u = std::max(0, x - r); u <= std::min(post.w - 1, x + r); ++u)
          n += std::abs(static_cast<int>(disp_value(post.at(u, v))) - d) <= 1;
      out.at<float>(y, x) = static_cast<float>(n);
    }
  return out;
}

// Per pixel: distance along its row to the nearest pixel the trellis left unmatched (64 cap).
cv::Mat row_distance_unmatched(const Evidence& ev) {
  const int w = ev.matched.w, h = ev.matched.h, cap = 64;
  cv::Mat out(h, w, CV_32F);
  std::vector<int> left(static_cast<size_t>(w));
  for (int y = 0; y < h; ++y) {
    int last = -cap;  // the last unmatched pixel at or left of x
    for (int x = 0; x < w; ++x) {
      if (!ev.matched.at(x, y)) last = x;
      left[static_cast<size_t>(x)] = x - last;
    }
    int next = w + cap;  // the first unmatched pixel at or right of x
    for (int x = w - 1; x >= 0; --x) {
      next = ev.matched.at(x, y) ? next : x;
      out.at<float>(y, x) = static_cast<float>(std::min({cap, left[static_cast<size_t>(x)], next - x}));
    }
  }
  return out;
}

// Mean |dI/dx| and standard deviation of the left image over side x side windows.
std::vector<cv::Mat> texture_maps(const cv::Mat& left) {
  cv::Mat l, gx;
  left.convertTo(l, CV_32F);
  cv::Sobel(l, gx, CV_32F, 1, 0, 3);
  gx = cv::abs(gx);
  std::vector<cv::Mat> out;
  for (int side : kTextureSides) {
    cv::Mat g, mu, mu2, var;
    cv::blur(gx, g, {side, side});
    cv::blur(l, mu, {side, side});
    cv::blur(l.mul(l), mu2, {side, side});
    cv::sqrt(cv::max(mu2 - mu.mul(mu), 0), var);
    out.push_back(g);
    out.push_back(var);
  }
  return out;
}

}  // namespace

const std::vector<std::string>& bound_feature_names() {
  static const std::vector<std::string> names = {"matched",
                                                 "gap",
                                                 "border (x < level)",
                                                 "|lr - d|",
                                                 "|d - dw|",
                                                 "ratio (9.3)",
                                                 "c1",
                                                 "c2 - c1",
                                                 "cmax - c1",
                                                 "filters changed the level",
                                                 "band curvature",
                                                 "support 3x3",
                                                 "support 5x5",
                                                 "support 15x15",
                                                 "row distance to unmatched",
                                                 "|Ix| mean 5x5",
                                                 "grey sd 5x5",
                                                 "|Ix| mean 15x15",
                                                 "grey sd 15x15",
                                                 "|Ix| mean 31x31",
                                                 "grey sd 31x31"};
  return names;
}

cv::Mat pixel_features(const OutputFrame& f) {
  const Evidence& e = f.ev;
  const int w = f.post.w, h = f.post.h;
  std::vector<cv::Mat> maps;
  for (int r : kSupportRadii) maps.push_back(level_support(f.post, r));
  maps.push_back(row_distance_unmatched(e));
  for (auto& m : texture_maps(f.left)) maps.push_back(m);
  cv::Mat x_out(w * h, static_cast<int>(bound_feature_names().size()), CV_32F);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int d = e.d.at(x, y), post_d = static_cast<int>(disp_value(f.post.at(x, y)));
      const int b1 = e.band[1].at(x, y), b2 = e.band[2].at(x, y), b3 = e.band[3].at(x, y);
      const float cols[] = {static_cast<float>(e.matched.at(x, y)),
                            static_cast<float>(std::min(64, static_cast<int>(e.gap.at(x, y)))),
                            static_cast<float>(x < post_d),
                            static_cast<float>(std::min(64, std::abs(e.lr.at(x, y) - d))),
                            static_cast<float>(std::min(64, std::abs(d - e.dw.at(x, y)))),
                            static_cast<float>(confidence(e, x, y, post_d) & 31),
                            static_cast<float>(e.c1.at(x, y)),
                            static_cast<float>(e.c2.at(x, y) - e.c1.at(x, y)),
                            static_cast<float>(e.cmax.at(x, y) - e.c1.at(x, y)),
                            static_cast<float>(post_d != d),
                            static_cast<float>(b1 + b3 - 2 * b2)};
      float* row = x_out.ptr<float>(y * w + x);
      std::copy(std::begin(cols), std::end(cols), row);
      for (size_t k = 0; k < maps.size(); ++k) row[std::size(cols) + k] = maps[k].at<float>(y, x);
    }
  return x_out;
}

namespace {

// The columns of pixel_features the configuration uses.
cv::Mat used_features(const OutputFrame& f, const BoundConfig& cfg) {
  const cv::Mat all = pixel_features(f);
  return cfg.evidence_only ? all.colRange(0, kEvidenceFeatures).clone() : all;
}

// The evaluated pixels' feature rows of one frame and their labels (1: dense output bad-1.0).
// `features`: the frame's used_features.
void labelled_rows(const OutputFrame& f, const cv::Mat& features, const cv::Mat& est, cv::Mat& rows, cv::Mat& labels) {
  for (int y = 0; y < f.gt.rows; ++y)
    for (int x = 0; x < f.gt.cols; ++x) {
      if (!evaluated(f.gt, f.mask, y, x)) continue;
      rows.push_back(features.row(y * f.gt.cols + x));
      const float e = est.at<float>(y, x);
      labels.push_back(e < 0 || std::fabs(e - f.gt.at<float>(y, x)) > 1.0f ? 1.0f : 0.0f);
    }
}

cv::Ptr<cv::ml::RTrees> train_forest(const cv::Mat& rows, const cv::Mat& labels, const BoundConfig& cfg) {
  cv::RNG rng(1);
  cv::Mat x, y;
  for (int i = 0; i < cfg.samples; ++i) {
    const int k = rng.uniform(0, rows.rows);
    x.push_back(rows.row(k));
    y.push_back(labels.row(k));
  }
  auto forest = cv::ml::RTrees::create();
  forest->setMaxDepth(cfg.depth);
  forest->setMinSampleCount(20);
  forest->setRegressionAccuracy(0);
  forest->setTermCriteria({cv::TermCriteria::MAX_ITER, cfg.trees, 0});
  forest->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, y));
  return forest;
}

// 255 - 255 p of every pixel, p the forest's estimate of the chance of bad-1.0.
cv::Mat forest_score(const cv::ml::RTrees& forest, const cv::Mat& features, int w, int h) {
  cv::Mat p;
  forest.predict(features, p);
  cv::Mat score(h, w, CV_8UC1);
  for (int i = 0; i < w * h; ++i)
    score.at<uint8_t>(i / w, i % w) = cv::saturate_cast<uint8_t>(255.0 - 255.0 * p.at<float>(i));
  return score;
}

}  // namespace

std::vector<cv::Mat> loso_scores(const std::vector<OutputFrame>& fr, const std::vector<cv::Mat>& est,
                                 const BoundConfig& cfg) {
  std::vector<cv::Mat> features(fr.size()), rows(fr.size()), labels(fr.size()), scores;
  for (size_t i = 0; i < fr.size(); ++i) {
    features[i] = used_features(fr[i], cfg);
    labelled_rows(fr[i], features[i], est[i], rows[i], labels[i]);
  }
  for (size_t i = 0; i < fr.size(); ++i) {
    fmt::print(stderr, "sm_output_study: bound, forest without {} ({}/{}) ...\n", fr[i].name, i + 1, fr.size());
    cv::Mat x, y;
    for (size_t j = 0; j < fr.size(); ++j)
      if (j != i) x.push_back(rows[j]), y.push_back(labels[j]);
    const auto forest = train_forest(x, y, cfg);
    scores.push_back(forest_score(*forest, features[i], fr[i].post.w, fr[i].post.h));
  }
  return scores;
}

void print_bound(const std::vector<OutputFrame>& fr, const std::vector<cv::Mat>& est,
                 const std::vector<cv::Mat>& score) {
  const double n = static_cast<double>(fr.size());
  fmt::print("\n| score >= t valid: t | density % | bad-1.0 of valid |\n|---:|---:|---:|\n");
  double best_dens = 0, b1v_at_85 = 0;
  for (int t = 0; t <= 255; ++t) {
    double dens = 0, b1v = 0;
    for (size_t i = 0; i < fr.size(); ++i) {
      cv::Mat e = est[i].clone();
      e.setTo(-1.0f, score[i] < t);
      const DispMetrics m = disp_metrics(e, fr[i].gt, fr[i].mask);
      dens += m.density() / n;
      b1v += m.bad1_of_valid() / n;
    }
    if (t % 10 == 0) fmt::print("| {} | {:.2f} | {:.2f} |\n", t, dens, b1v);
    if (b1v <= kGoalBad1) best_dens = std::max(best_dens, dens);
    if (dens >= kGoalDensity) b1v_at_85 = b1v;
  }
  double auc = 0, oauc = 0;
  for (size_t i = 0; i < fr.size(); ++i) {
    const Sparsification s = sparsification(est[i], score[i], fr[i].gt, fr[i].mask);
    auc += s.auc / n;
    oauc += s.oracle_auc / n;
  }
  fmt::print(
      "\nValidity: highest density with bad-1.0 of valid <= 5.0: {:.2f} %; bad-1.0 of valid at the "
      "last t with density >= 85 %: {:.2f}\n",
      best_dens, b1v_at_85);
  fmt::print("Confidence = score: sparsification AUC {:.3f}, oracle {:.3f}, {:.2f}x\n", auc, oauc, auc / oauc);
}

}  // namespace sm::tools
