// stereo_sim's pictures (sm_sim_pictures.hpp).
#include "sm_sim_pictures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "toolio/sm_io.hpp"

namespace sm::simapp {

namespace {

// A tile of the panel with its label in the top-left corner.
cv::Mat labelled(const cv::Mat& img, const std::string& label) {
  cv::Mat t = img.clone();
  const double scale = std::max(0.3, t.cols / 800.0);
  int base = 0;
  const cv::Size ts = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
  cv::rectangle(t, cv::Rect(0, 0, std::min(t.cols, ts.width + 4), std::min(t.rows, ts.height + base + 4)),
                cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(t, label, cv::Point(2, ts.height + 2), cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  return t;
}

// Error map against ground truth: green = within 1 px, red = off by more, magenta = no
// estimate, dark grey = not evaluated (unknown ground truth or occluded).
cv::Mat error_map(const cv::Mat& est, const cv::Mat& gt, const cv::Mat& mask) {
  cv::Mat m(gt.size(), CV_8UC3, cv::Scalar(40, 40, 40));
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x) {
      const float g = gt.at<float>(y, x);
      if (!(g > 0) || (!mask.empty() && mask.at<uint8_t>(y, x) == 0)) continue;
      const float e = est.at<float>(y, x);
      m.at<cv::Vec3b>(y, x) =
          e < 0 ? cv::Vec3b(255, 0, 255) : (std::fabs(e - g) > 1.0f ? cv::Vec3b(0, 0, 255) : cv::Vec3b(0, 160, 0));
    }
  return m;
}

cv::Mat bgr(const Image8& im) {
  cv::Mat c;
  cv::cvtColor(tools::to_mat(im), c, cv::COLOR_GRAY2BGR);
  return c;
}

// The panel's last row: error map and ground truth.
cv::Mat ground_truth_row(const HwConfig& hw, const SimInput& in, const cv::Mat& disp, double bad1) {
  cv::Mat gt_f = in.gt.clone();
  gt_f.setTo(-1.0f, in.gt <= 0);
  cv::Mat row;
  cv::hconcat(labelled(error_map(disp, in.gt, in.mask), fmt::format("error map (bad-1.0 {:.1f} %)", bad1)),
              labelled(tools::disp_to_colour(gt_f, hw.disp), "ground truth"), row);
  return row;
}

}  // namespace

void write_disparity_pictures(const std::string& dir, const cv::Mat& disp, const HwConfig& hw) {
  tools::write_image_atomic(dir + "/disparity.png", tools::disp_to_grey(disp, hw.disp));
  tools::write_image_atomic(dir + "/disparity_color.png", tools::disp_to_colour(disp, hw.disp));
}

void write_panel(const std::string& dir, const HwConfig& hw, const SimInput& in, const RegisterPlan& plan,
                 const ModelCheck& check, const std::vector<ObjectPacket>& packets, const cv::Mat& disp, double bad1) {
  const auto& frame = check.last_input;
  const PipelineResult m =
      !check.last_model ? run_pipeline(frame.first, frame.second, hw, plan.regs.back(), false) : *check.last_model;
  const cv::Mat colour = tools::disp_to_colour(disp, hw.disp);
  cv::Mat objects = colour.clone();
  const std::vector<Object>& boxes = packets.empty() ? m.objects.objects : packets.back().objects;
  for (const auto& o : boxes)
    cv::rectangle(objects, cv::Point(o.x0, o.y0), cv::Point(o.x1, o.y1), cv::Scalar(255, 255, 255), 1);
  std::vector<cv::Mat> rows(3);
  cv::hconcat(labelled(bgr(frame.first), "left"), labelled(bgr(frame.second), "right"), rows[0]);
  cv::hconcat(labelled(bgr(m.rl), "rectified left"), labelled(bgr(m.rr), "rectified right"), rows[1]);
  cv::hconcat(labelled(colour, "disparity"), labelled(objects, fmt::format("objects ({})", boxes.size())), rows[2]);
  if (!in.gt.empty()) rows.push_back(ground_truth_row(hw, in, disp, bad1));
  cv::Mat panel;
  cv::vconcat(rows, panel);
  tools::write_image_atomic(dir + "/panel.png", panel);
}

}  // namespace sm::simapp
