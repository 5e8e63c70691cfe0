// stereo_sim's lossless disparity files (sm_sim_outputs.hpp).
#include "sm_sim_outputs.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"

namespace fs = std::filesystem;

namespace sm::simapp {

std::string frame_disparity_path(const std::string& disp_file, size_t f) {
  const fs::path p(disp_file);
  return (p.parent_path() / fmt::format("{}_{:03d}{}", p.stem().string(), f, p.extension().string())).string();
}

void write_disparity_files(tools::OutputSet& outs, const SimOptions& opt, const cv::Mat& disp) {
  outs.write(
      opt.disp_file, [&](const std::string& temp) { tools::write_disparity_file(temp, disp); }, true);
}

FrameFiles::~FrameFiles() {
  if (kept_) return;
  std::error_code ec;
  for (const auto& p : written_) fs::remove(p, ec);
}

void FrameFiles::write(size_t f, const OutImage& disp) {
  const std::string path = frame_disparity_path(disp_file_, f);
  if (written_.empty()) {
    const fs::path dir = fs::path(path).parent_path();
    if (!dir.empty()) fs::create_directories(dir);
  }
  on_signal_.emplace_back(path);
  written_.push_back(path);  // before writing: a failed write's part is removed too
  tools::write_disparity_file(path, tools::out_to_float(disp));
}

}  // namespace sm::simapp
