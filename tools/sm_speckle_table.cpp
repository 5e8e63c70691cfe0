#include "sm_speckle_table.hpp"

#include <cstdint>

namespace sm::tools {

cv::Mat speckle_keep_table(const cv::Mat& q4, int max_size, int max_diff, int delay_rows, int labels,
                           SpeckleStats* stats) {
  CV_Assert(q4.type() == CV_16S && max_size >= 0 && max_size <= 4095 && max_diff >= 0 && max_diff <= 255);
  OutImage words(q4.cols, q4.rows);
  for (int y = 0; y < q4.rows; ++y)
    for (int x = 0; x < q4.cols; ++x) {
      const int v = q4.at<int16_t>(y, x);
      words.at(x, y) = make_out_word(v >= 0, 0, static_cast<unsigned>(v >= 0 ? v : 0));
    }
  SpeckleRegs regs;
  regs.en = 1;
  regs.size = static_cast<uint16_t>(max_size);
  regs.diff = static_cast<uint8_t>(max_diff);
  regs.trust = 4095;  // the maps carry no confidence: no region is trusted
  const OutImage out = speckle_output(words, regs, delay_rows, labels, stats);
  cv::Mat keep = cv::Mat::zeros(q4.rows, q4.cols, CV_8U);
  for (int y = 0; y < q4.rows; ++y)
    for (int x = 0; x < q4.cols; ++x) keep.at<uint8_t>(y, x) = out_valid(out.at(x, y));
  return keep;
}

}  // namespace sm::tools
