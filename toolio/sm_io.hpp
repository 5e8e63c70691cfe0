// Helpers shared by the command-line tools (sm_scene, stereo_model, sm_evaluate):
// image loading with one-line errors, atomic output files, disparity colour maps, the
// stereo-dataset reader (../shared/datasets layout), the bad-1.0 metric and the streak measure.
// See docs/evaluation.md.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sm_types.hpp"

namespace CLI {
class App;
}

namespace sm::tools {

// Every user-facing failure of a tool: the message is one line naming the file/problem.
struct ToolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A tool's main(): runs `run` and turns any exception into the one-line error
// "<tool>: error: <what>" on stderr and exit code 1, or 2 for a command-line error
// (run_guarded, kExitError / kExitUsage of toolio/sm_cli.hpp).
int guarded_main(const char* tool, int (*run)(int, char**), int argc, char** argv);

// Parses a tool's command line into `app`: 0 when the tool stops there (--help, printed by
// CLI11), nothing when it goes on; a parse error throws UsageError (toolio/sm_cli.hpp)
// with CLI11's message, which guarded_main prints as one line and exits 2.
std::optional<int> parse_args(CLI::App& app, int argc, char** argv);

// The disparity levels of the model and the RTL (DISP): even, 4..254; a ToolError
// "<option> <levels>: must be even, 4..254" otherwise. per_scene: 0 is taken too (the tools
// whose 0 means "each scene's own levels"), and the error says so.
void check_levels(const char* option, int levels, bool per_scene = false);

// An input file that must exist and be readable, checked before any work: a ToolError
// "<path>: no such file", "<path>: is a directory" or "<path>: cannot read: <reason>".
void check_input_file(const std::string& path);

// Silences OpenCV's own logging (tools report errors themselves, in one line).
void quiet_opencv();

// Parks stderr on /dev/null while it lives: libpng and FFmpeg print their own complaints
// ("[png @ 0x...] ...") on stderr past OpenCV's log level, and the tools promise one
// error line of their own.
class StderrMute {
 public:
  StderrMute();
  ~StderrMute();
  StderrMute(const StderrMute&) = delete;
  StderrMute& operator=(const StderrMute&) = delete;

 private:
  int saved_ = -1;
};

// Reads an image file (PNG/JPEG/...) with cv::imread flags; throws ToolError when the
// file is missing, unreadable or not a decodable image (libpng's chatter is suppressed).
cv::Mat read_image(const std::string& path, int flags);

// 8-bit grey image: colour inputs are converted with OpenCV's BGR->grey weights.
cv::Mat load_grey_mat(const std::string& path);
Image8 load_grey(const std::string& path);

Image8 to_image8(const cv::Mat& grey);  // CV_8UC1 -> Image8
cv::Mat to_mat(const Image8& img);      // Image8 -> CV_8UC1 (copy)

// Writes an image so that no partial file is ever left under `path`: encode to a
// temporary name in the same directory, then rename (`params`: cv::imwrite's, e.g. the PNG
// compression level). Throws ToolError.
void write_image_atomic(const std::string& path, const cv::Mat& img, const std::vector<int>& params = {});
void write_text_atomic(const std::string& path, const std::string& text);
// The same for a JSON document, indented by 2 and ended by a newline (streamed to the file).
void write_json_atomic(const std::string& path, const nlohmann::json& j);

// Disparity as float pixels, negative = invalid (no output).
cv::Mat disp_to_float(const DispImage& d);
// The 8-bit grey preview (stereo_model -o, stereo_sim's disparity.png): invalid (negative,
// NaN or infinite) = 0, a valid disparity d = 1 + round(min(d, levels - 1) * 254 /
// (levels - 1)), so disparity 0 (grey 1) and invalid (grey 0) differ.
cv::Mat disp_to_grey(const cv::Mat& disp_f, int levels);
// Colour rendering: the turbo colour map of disp_to_grey (disparity 0..levels-1 over grey
// 1..255), invalid = black.
cv::Mat disp_to_colour(const cv::Mat& disp_f, int levels);

// Lossless disparity files, the format chosen by the extension of `path`:
// - .png: 16-bit grey, value = round(disparity * 16), 0 = invalid (the KITTI convention;
//   disparities above 4095.9 or exactly 0 cannot be told from invalid / are clipped);
// - .pfm: one-channel 32-bit float (the Middlebury convention), +infinity = invalid.
// disp_f is CV_32F with negative = invalid (as from disp_to_float). Written atomically
// (write_image_atomic); any other extension is a ToolError naming the file.
void write_disparity_file(const std::string& path, const cv::Mat& disp_f);
// Reads such a file back as CV_32F, negative (-1) = invalid: a 16-bit (or 8-bit) PNG is
// divided by png_scale with 0 = invalid; a PFM's non-finite values are invalid. Throws
// ToolError naming the file for a missing/unreadable file or an unsupported format.
cv::Mat read_disparity_file(const std::string& path, double png_scale = 16);

// One scene of a stereo dataset: folder with left.png right.png gt.png scale.txt and an
// optional nonocc.png (../shared/datasets/README.md; sm_scene writes the same layout).
struct Scene {
  std::string name;
  std::string dir;
  cv::Mat left, right;  // CV_8UC1 grey
  cv::Mat gt;           // CV_32F disparity = value / scale; 0 = unknown
  cv::Mat nonocc;       // CV_8UC1 (255 = visible in the right view) or empty
  double scale = 1;
  int levels = 0;  // disparity levels the scene needs (scale.txt)
};
bool is_scene_dir(const std::string& dir);
Scene load_scene(const std::string& dir);
// Scene folders below `root` (sorted by name), or `root` itself if it is a scene.
std::vector<std::string> list_scenes(const std::string& root);

// bad-1.0: percentage of evaluated pixels (gt > 0, and nonocc where present) whose
// disparity differs from gt by more than 1; invalid estimates (< 0) count as bad.
struct BadStats {
  long evaluated = 0;
  long bad = 0;
  long invalid = 0;  // evaluated pixels without an estimate (also in bad)
  double bad_pct() const { return evaluated ? 100.0 * bad / evaluated : 0.0; }
};
BadStats bad1(const cv::Mat& est_f, const cv::Mat& gt, const cv::Mat& mask);

// Streak measure (docs/evaluation.md, "Streaks and fair peers"): the share of pixels whose
// ground truth is vertically smooth that are horizontal-streak errors. A pixel (x, y) is
// *smooth* when it and both vertical neighbours (x, y-1), (x, y+1) are evaluated pixels of
// bad1 (gt > 0, mask set where given) with |gt(y-1) - gt(y)| <= 1 and |gt(y+1) - gt(y)| <= 1
// (so the first and last rows never are); this set, the denominator, depends on the
// ground truth only. A smooth pixel is a *streak* pixel (of at most max_rows rows) when its
// estimate d is valid (>= 0) and bad (|d - gt(y)| > 1) and there are du, dd >= 1 with
// du + dd <= max_rows + 1 such that the estimates at y - du and y + dd are valid and differ
// from d by more than 1, every row y - du .. y + dd of the column is evaluated and its gt is
// within 1 of gt(y). max_rows = 1: the pixel disagrees with both vertical neighbours while
// the truth is smooth; larger: it lies in a band of at most max_rows rows between two rows
// that disagree with it. Invalid estimates are never streaks (bad1 counts them).
struct StreakStats {
  long smooth = 0;  // smooth pixels (the denominator)
  long streak = 0;  // of those, streak pixels
  double streak_pct() const { return smooth ? 100.0 * streak / smooth : 0.0; }
};
StreakStats streaks(const cv::Mat& est_f, const cv::Mat& gt, const cv::Mat& mask, int max_rows = 1);

}  // namespace sm::tools
