// How far any function of the output stage's evidence can go (sm_output_study --study
// bound, docs/evaluation.md "What the evidence allows"): a random forest, trained on every
// scene but one and scored on that one (leave one scene out), predicts from each pixel's
// evidence whether the dense output is bad-1.0 there. Its 8-bit score is then scored as
// the checked mode's validity (density against bad-1.0 of the valid pixels) and as the
// confidence (sparsification against the oracle), the goals of issue 39. The forest also
// sees texture of the left image and windows of the output level the stage does not keep,
// so it is an optimistic stand-in for a better rule or confidence formula.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "output_frame.hpp"

namespace sm::tools {

// Feature names, one per column of pixel_features; the first kEvidenceFeatures are the
// output stage's own per-pixel evidence (docs/algorithm.md 9.0), the rest need windows
// the stage does not keep.
const std::vector<std::string>& bound_feature_names();
constexpr int kEvidenceFeatures = 11;

// Every pixel's features (rows y * w + x, CV_32F, one column per bound_feature_names entry).
cv::Mat pixel_features(const OutputFrame& f);

struct BoundConfig {
  int samples = 100000;  // training pixels drawn (fixed seed) from the other scenes
  int trees = 50;
  int depth = 10;
  bool evidence_only = false;  // the first kEvidenceFeatures columns only
};

// The forest's 8-bit score (255 = surely good) of every pixel of each frame, each frame's
// forest trained on the others (leave one scene out). est: each frame's dense output
// (CV_32F, the pixels' labels: |est - gt| > 1).
std::vector<cv::Mat> loso_scores(const std::vector<OutputFrame>& fr, const std::vector<cv::Mat>& est,
                                 const BoundConfig& cfg);

// Prints the validity sweep (score >= t valid) and the sparsification of the scores.
void print_bound(const std::vector<OutputFrame>& fr, const std::vector<cv::Mat>& est,
                 const std::vector<cv::Mat>& score);

}  // namespace sm::tools
