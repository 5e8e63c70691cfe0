// A synthetic chessboard stereo rig for the calibration tool's tests (test_tools_cli,
// test_depth): Catch2 must be included first.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace sm::test {

// A synthetic stereo rig looking at a 9x6 chessboard (inner corners) from several poses:
// pinhole cameras (f 600 px, 640x480, no distortion), right camera 2 squares to the right
// and rolled by 1.5 degrees, board about 20 squares away. Writes leftNN.png / rightNN.png.
inline void write_chessboard_rig(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const int S = 32;  // texture pixels per square; one white square of margin around
  cv::Mat tex(9 * S, 12 * S, CV_8UC1, cv::Scalar(255));
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 10; ++j)
      if ((i + j) % 2 == 0) tex(cv::Rect((j + 1) * S, (i + 1) * S, S, S)).setTo(0);
  const cv::Matx33d K(600, 0, 319.5, 0, 600, 239.5, 0, 0, 1);
  const cv::Matx33d A(1.0 / S, 0, -1, 0, 1.0 / S, -1, 0, 0, 1);  // texture pixel -> board (squares)
  auto rot = [](double ax, double ay, double az) {
    const double a = ax * CV_PI / 180, b = ay * CV_PI / 180, c = az * CV_PI / 180;
    const cv::Matx33d rx(1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a));
    const cv::Matx33d ry(std::cos(b), 0, std::sin(b), 0, 1, 0, -std::sin(b), 0, std::cos(b));
    const cv::Matx33d rz(std::cos(c), -std::sin(c), 0, std::sin(c), std::cos(c), 0, 0, 0, 1);
    return rz * ry * rx;
  };
  const cv::Matx33d r_rig = rot(0, 0, 1.5);
  const cv::Vec3d t_rig(-2, 0, 0);
  // tilt about x and y (degrees), board centre (x, y) at depth 20
  const double poses[][4] = {{0, 0, 1, 0},     {20, 0, 1, 0},    {-20, 0, 1, 0},   {0, 25, 1, 0},   {0, -25, 1, 0},
                             {15, 15, -3, -3}, {-15, 20, 5, -3}, {10, -15, -3, 3}, {-10, -10, 5, 3}};
  int n = 0;
  for (const auto& p : poses) {
    const cv::Matx33d r = rot(p[0], p[1], 0);
    const cv::Vec3d t = cv::Vec3d(p[2], p[3], 20) - r * cv::Vec3d(5, 3.5, 0);
    for (int cam = 0; cam < 2; ++cam) {
      const cv::Matx33d rc = cam ? r_rig * r : r;
      const cv::Vec3d tc = cam ? r_rig * t + t_rig : t;
      const cv::Matx33d rt(rc(0, 0), rc(0, 1), tc[0], rc(1, 0), rc(1, 1), tc[1], rc(2, 0), rc(2, 1), tc[2]);
      cv::Mat img;
      cv::warpPerspective(tex, img, cv::Mat(K * rt * A), cv::Size(640, 480), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                          cv::Scalar(160));
      REQUIRE(cv::imwrite((dir / fmt::format("{}{:02d}.png", cam ? "right" : "left", n)).string(), img));
    }
    ++n;
  }
}

}  // namespace sm::test
