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

}  // namespace

void write_disparity_files(const SimOptions& opt, const SimResult& res, const cv::Mat& disp) {
  tools::write_disparity_file(opt.disp_file, disp);
  if (!opt.disp_each) return;
  for (size_t f = 0; f < res.frames.size(); ++f)
    tools::write_disparity_file(frame_path(opt.disp_file, f), tools::disp_to_float(res.frames[f]));
}

}  // namespace sm::simapp
