// stereo_sim's lossless disparity files (sm_sim_outputs.hpp).
#include "sm_sim_outputs.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "toolio/sm_io.hpp"

namespace fs = std::filesystem;

namespace sm::simapp {

namespace {

// <stem>_<frame><ext> beside `path`.
std::string frame_path(const std::string& path, size_t f) {
  const fs::path p(path);
  return (p.parent_path() / fmt::format("{}_{:03d}{}", p.stem().string(), f, p.extension().string())).string();
}

void stage_disparity(tools::OutputSet& outs, const std::string& path, const cv::Mat& disp) {
  outs.write(
      path, [&](const std::string& temp) { tools::write_disparity_file(temp, disp); }, true);
}

}  // namespace

void write_disparity_files(tools::OutputSet& outs, const SimOptions& opt, const SimResult& res, const cv::Mat& disp) {
  stage_disparity(outs, opt.disp_file, disp);
  if (!opt.disp_each) return;
  for (size_t f = 0; f < res.frames.size(); ++f)
    stage_disparity(outs, frame_path(opt.disp_file, f), tools::disp_to_float(res.frames[f]));
}

}  // namespace sm::simapp
