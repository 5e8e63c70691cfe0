// stereo_model: runs the bit-exact reference model (model/pipeline.hpp) on one stereo
// pair and writes the disparity losslessly (--disp-file: PFM, or 16-bit PNG x16; --mode dense /
// checked: the Q.4 sub-pixel output, checked with invalid pixels, and --confidence) and/or
// for viewing as a grey PNG (0..255 over 0..DISP-1, invalid = 0) and a colour-mapped PNG.
// Every HwConfig / Regs field can be set by option or by a --regs JSON file (keys = field
// names; its width / height resize the images to that active size, as in stereo_sim);
// options given on the command line win. With a calibration that holds the rectified
// camera, metric depth (--depth-file) and a point cloud (--cloud, --cloud-view). --speckle
// adds the host's speckle check (toolio/sm_host_speckle.hpp) before every output. Outputs
// are checked writable before any work and written all-or-nothing.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "calib_file.hpp"
#include "configs.hpp"
#include "toolio/sm_depth_options.hpp"
#include "toolio/sm_host_speckle.hpp"
#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_metrics.hpp"
#include "toolio/sm_object_flags.hpp"
#include "toolio/sm_objects_json.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_param_in.hpp"
#include "toolio/sm_pictures.hpp"
#include "toolio/sm_reg_options.hpp"
#include "toolio/sm_regs_json.hpp"
#include "outword.hpp"
#include "pipeline.hpp"
#include "smooth.hpp"
#include "sm_defs.hpp"
#include "lower_case.hpp"

namespace {

using sm::tools::ToolError;
using json = nlohmann::json;

// The outputs, checked before any work: at least one, --disp-file .pfm or .png, every one
// writable, no two the same file, none an input. Sets the default --colour (<out>_colour.png with -o).
void check_outputs(const std::string& out, std::string& colour, const std::string& disp_file,
                   const std::string& objects_json, const std::string& conf_png, const sm::tools::DepthOptions& depth,
                   const sm::tools::PathList& inputs) {
  if (out.empty() && colour.empty() && disp_file.empty() && objects_json.empty() && conf_png.empty() && !depth.any())
    throw ToolError("no output: give -o, --colour, --disp-file, --objects-json, --depth-file and/or --cloud");
  if (!disp_file.empty()) {
    const std::string ext = sm::lower_extension(disp_file);
    if (ext != ".pfm" && ext != ".png")
      throw ToolError(fmt::format("{}: --disp-file must end in .pfm or .png", disp_file));
  }
  if (colour.empty() && !out.empty()) {
    const std::filesystem::path p(out);
    colour = (p.parent_path() / (p.stem().string() + "_colour.png")).string();
  }
  sm::tools::check_outputs({{"-o", out},
                            {"--colour", colour},
                            {"--disp-file", disp_file},
                            {"--objects-json", objects_json},
                            {"--confidence", conf_png},
                            {"--depth-file", depth.depth_file},
                            {"--cloud", depth.cloud},
                            {"--cloud-view", depth.cloud_view}},
                           false, inputs);
}

// The input images resized to the register file's active size (as stereo_sim resizes
// its inputs), with a note on stderr.
void resize_to_active(cv::Mat& left, cv::Mat& right, int w, int h, const std::string& regs) {
  if (left.cols == w && left.rows == h) return;
  fmt::print(stderr, "stereo_model: note: the images ({}x{}) are resized to the active size {}x{} of {}\n", left.cols,
             left.rows, w, h, regs);
  for (cv::Mat* m : {&left, &right}) {
    cv::Mat resized;
    cv::resize(*m, resized, cv::Size(w, h), 0, 0, cv::INTER_AREA);
    *m = resized;
  }
}

int run(int argc, char** argv) {
  std::string left, right, out, colour, disp_file, regs_json, calib, stage = "post", objects_json;
  sm::HwConfig hw;
  sm::Regs r = sm::Regs::defaults(hw);
  // Option defaults shown by --help are the model's own (HwConfig / Regs::defaults).
  bool no_rect = !r.rect_enable, verbose = false;
  int threads = 1;
  // --help shows the table up to its last non-zero code
  std::vector<int> sw_table(r.sw_table.begin(), r.sw_table.end());
  while (sw_table.size() > 1 && sw_table.back() == 0) sw_table.pop_back();
  CLI::App app{"Bit-exact reference model of the census stereo IP on one image pair"};
  app.add_option("left", left, "left image (PNG/JPEG; reference view)")->required();
  app.add_option("right", right, "right image")->required();
  app.add_option("-o,--out", out, "disparity PNG for viewing (grey, 0..255 over 0..DISP-1, invalid = 0)");
  app.add_option("--colour", colour,
                 "colour-mapped disparity PNG over the data's range, with a colour bar (depth ticks with a "
                 "calibrated camera) and the invalid colour (default with -o: <out>_colour.png)");
  app.add_option("--disp-file", disp_file,
                 "lossless disparity: .pfm = float PFM (+inf = invalid, Middlebury), .png = 16-bit PNG of "
                 "disparity x 16 (0 = invalid, KITTI)");
  app.add_option("--stage", stage, "disparity written: dp (trellis output) or post (filtered)")
      ->check(CLI::IsMember({"dp", "post"}))
      ->capture_default_str();
  app.add_option("--objects-json", objects_json, "write the object list as JSON");
  std::string mode = "integer", conf_png;
  app.add_option("--mode", mode,
                 "disparity written: integer (the --stage output), dense (post + Q.4 fraction, every pixel valid) or "
                 "checked (Q.4, pixels failing the validity rules invalid) -- the planned output word, "
                 "model/outword.hpp")
      ->check(CLI::IsMember({"integer", "dense", "checked"}))
      ->capture_default_str();
  app.add_option("--confidence", conf_png, "write the 8-bit confidence of --mode dense/checked as a grey PNG");
  std::string config = "paper";
  app.add_option("--config", config,
                 "the configuration whose parameters and register resets it models (sizes: the image's; --regs "
                 "and the options below apply on top)")
      ->check(CLI::IsMember(sm::config_names()))
      ->capture_default_str();
  app.add_option("--regs", regs_json, "JSON file of HwConfig/Regs fields (keys = field names)");
  app.add_option("--calib", calib, "calibration JSON (model/calib_file.hpp): rectification grids");
  // each option by the sm_top parameter it sets (HwConfig::field)
  const std::vector<std::pair<const char*, CLI::Option*>> hw_opts = {
      {"MAX_WIDTH", app.add_option("--max-width", hw.max_width, "MAX_WIDTH (default: image width)")},
      {"MAX_HEIGHT", app.add_option("--max-height", hw.max_height, "MAX_HEIGHT (default: image height)")},
      {"DISP", app.add_option("--disp", hw.disp, "DISP: disparity levels")->capture_default_str()},
      {"CENSUS", app.add_option("--census", hw.census, "CENSUS: census window side")->capture_default_str()},
      {"SW", app.add_option("--sw", hw.sw, "SW: support-weight window side")->capture_default_str()},
      {"RECT_RADIUS", app.add_option("--rect-radius", hw.rect_radius, "RECT_RADIUS")->capture_default_str()},
      {"COST_SHIFT", app.add_option("--cost-shift", hw.cost_shift, "COST_SHIFT")->capture_default_str()},
      {"MAX_OBJECTS", app.add_option("--max-objects", hw.max_objects, "MAX_OBJECTS")->capture_default_str()},
      {"LABEL_SLOTS", app.add_option("--label-slots", hw.label_slots, "LABEL_SLOTS")->capture_default_str()},
      {"BAND_K",
       app.add_option("--band-k", hw.band_k, "BAND_K: look-ahead rows of the band filter F0")->capture_default_str()},
      {"AD_SHIFT", app.add_option("--ad-shift", hw.ad_shift,
                                  "AD_SHIFT: the cost's intensity term is |L - R| >> "
                                  "AD_SHIFT")
                       ->capture_default_str()},
      {"AD_MAX", app.add_option("--ad-max", hw.ad_max, "AD_MAX: the intensity term's cap (0: census only)")
                     ->capture_default_str()},
      {"SPECKLE_ROWS", app.add_option("--speckle-rows", hw.speckle_rows,
                                      "SPECKLE_ROWS: the speckle stage's rows (0: none; the zynq configuration: 32; "
                                      "the stage then resets into its speckle mode: SPECKLE_EN 1, LR_EN 0, AGREE_EN 0)")
                           ->capture_default_str()},
      {"SPECKLE_LABELS",
       app.add_option("--speckle-labels", hw.speckle_labels, "SPECKLE_LABELS: its label-table entries")
           ->capture_default_str()}};
  // each parameter's own range is a parse error (exit 2); combinations are checked below
  for (const auto& [name, opt] : hw_opts) opt->check(sm::tools::param_in(name));
  // the value registers (the active size comes from the images, RECT_ENABLE is --no-rect)
  // ranges in --help at the default configuration (--disp, ... may change them)
  const sm::tools::RegOptions reg_opts(app, r, hw, {"WIDTH", "HEIGHT", "RECT_ENABLE"});
  auto* o_nr = app.add_flag("--no-rect", no_rect, "rect_enable = 0 (rectifier passes pixels through)");
  auto* o_swt = app.add_option("--sw-table", sw_table, "weight codes 0..3 by |dI|>>3, comma-separated (1..32)")
                    ->delimiter(',')
                    ->check(sm::tools::int_in(0, 3))
                    ->default_str(fmt::format("{}", fmt::join(sw_table, ",")));
  app.add_option("--threads", threads, "threads of the model, 1..256 (same output for any count)")
      ->check(sm::tools::int_in(1, 256))
      ->capture_default_str();
  app.add_flag("-v,--verbose", verbose, "print per-stage timing");
  sm::tools::DepthOptions depth;
  depth.add(app);
  sm::tools::HostSpeckleOptions speckle;
  speckle.add(app);
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;

  check_outputs(out, colour, disp_file, objects_json, conf_png, depth,
                {{"left", left}, {"right", right}, {"--regs", regs_json}, {"--calib", calib}});
  if (!regs_json.empty()) sm::tools::check_input_file(regs_json);
  if (!calib.empty()) sm::tools::check_input_file(calib);
  if (mode != "integer" && stage == "dp")
    throw ToolError("--mode " + mode + " works on the post output, not --stage dp");
  if (mode == "integer" && !conf_png.empty()) throw ToolError("--confidence needs --mode dense or checked");
  sm::tools::quiet_opencv();
  cv::Mat left_m = sm::tools::load_grey_mat(left), right_m = sm::tools::load_grey_mat(right);
  if (left_m.size() != right_m.size())
    throw ToolError(fmt::format("{}: size {}x{} differs from {} ({}x{})", right, right_m.cols, right_m.rows, left,
                                left_m.cols, left_m.rows));

  // The configuration (MAX_WIDTH x MAX_HEIGHT = active size = image size) and its resets,
  // then --regs, then explicit options. The file may set the active size (width, height):
  // checked against its own MAX_WIDTH / MAX_HEIGHT or the largest the IP allows, the images
  // are resized to it.
  const sm::HwConfig cli_hw = hw;
  hw = sm::named_config(config);
  sm::set_config_resets(hw, r);
  hw.max_width = left_m.cols;
  hw.max_height = left_m.rows;
  int act_w = left_m.cols, act_h = left_m.rows;
  sm::tools::RegsFile file_keys;  // what --regs sets
  if (!regs_json.empty()) {
    hw.max_width = sm::defs::limit("MAX_WIDTH").max;
    hw.max_height = sm::defs::limit("MAX_HEIGHT").max;
    r.width = act_w;
    r.height = act_h;
    file_keys = sm::tools::apply_regs_json(regs_json, hw, r);
    if (calib.empty()) calib = file_keys.calib;  // the file's "calib" key, unless --calib is given
    act_w = r.width;
    act_h = r.height;
    if (!file_keys.has("max_width")) hw.max_width = act_w;
    if (!file_keys.has("max_height")) hw.max_height = act_h;
    resize_to_active(left_m, right_m, act_w, act_h, regs_json);
  }
  const sm::Image8 L = sm::tools::to_image8(left_m);
  const sm::Image8 R = sm::tools::to_image8(right_m);
  bool cli_hw_set = false;
  for (const auto& [name, opt] : hw_opts)
    if (opt->count()) {
      *hw.field(name) = *cli_hw.field(name);
      cli_hw_set = true;
    }
  // the resets of the configuration the options changed, but for the file's registers
  if (cli_hw_set) sm::tools::set_config_resets_keeping(file_keys, hw, r);
  try {
    hw.validate();
  } catch (const std::invalid_argument& e) {
    throw ToolError(fmt::format("bad hardware configuration: {}", e.what()));
  }
  if (L.w > hw.max_width || L.h > hw.max_height)
    throw ToolError(fmt::format("{}: size {}x{} above MAX_WIDTH x MAX_HEIGHT = {}x{}", left, L.w, L.h, hw.max_width,
                                hw.max_height));
  if (L.w < 16 || L.h < 16) throw ToolError(fmt::format("{}: size {}x{} below 16x16", left, L.w, L.h));
  r.width = L.w;
  r.height = L.h;
  r.grid_l = sm::RectGrid::identity(L.w, L.h);
  r.grid_r = r.grid_l;
  reg_opts.apply(hw, r);
  if (o_nr->count()) r.rect_enable = !no_rect;
  if (o_swt->count()) {
    if (sw_table.empty() || sw_table.size() > r.sw_table.size())
      throw ToolError("--sw-table: expected 1..32 comma-separated codes");
    r.sw_table.fill(0);
    std::copy(sw_table.begin(), sw_table.end(), r.sw_table.begin());
  }
  std::optional<sm::RectCamera> camera;
  if (!calib.empty()) {
    sm::CalibFile c;
    try {
      c = sm::load_fitting_calib(calib, hw);
    } catch (const std::exception& e) {
      throw ToolError(e.what());
    }
    if (c.width != L.w || c.height != L.h)
      throw ToolError(
          fmt::format("{}: calibration is for {}x{}, images are {}x{}", calib, c.width, c.height, L.w, L.h));
    r.grid_l = c.left;
    r.grid_r = c.right;
    if (!o_nr->count()) r.rect_enable = true;
    camera = c.camera;
  }
  depth.check(camera, calib);

  sm::PipelineResult res;
  try {
    res = sm::run_pipeline(L, R, hw, r, false, threads);
  } catch (const std::invalid_argument& e) {
    throw ToolError(fmt::format("bad configuration: {}", e.what()));
  }
  const sm::DispImage& d = stage == "dp" ? res.dp : res.post;
  // checked: the words run_pipeline made at these registers; dense: the same stages without the rules
  const sm::OutImage word = mode == "integer" ? sm::OutImage{}
                            : mode == "dense"
                                ? sm::stream_words(res.evidence, res.post, hw.disp, sm::dense_mode(sm::output_regs(r)))
                                : res.out;
  cv::Mat df = mode == "integer" ? sm::tools::disp_to_float(d) : sm::tools::out_to_float(word);
  const long speckled = speckle.apply(df);  // the host's check, before every output made from df
  if (speckle.on() && mode == "checked" && (r.lr_en || r.agree_en || r.smooth_en))
    fmt::print(stderr,
               "stereo_model: note: --speckle was measured with --lr-en 0 --agree-en 0 --smooth-en 0 (docs/"
               "evaluation.md, \"Speckles\"); with them on it does worse\n");
  // All outputs under temporary names first, renamed together once every one is written.
  sm::tools::OutputSet outs;
  if (!out.empty())
    outs.write(out,
               [&](const std::string& t) { sm::tools::write_image_atomic(t, sm::tools::disp_to_grey(df, hw.disp)); });
  if (!colour.empty())
    outs.write(colour, [&](const std::string& t) {
      const cv::Mat pic = sm::tools::disparity_picture(df, sm::tools::data_range(df), camera ? &*camera : nullptr);
      sm::tools::write_image_atomic(t, pic);
    });
  if (!disp_file.empty()) outs.write(disp_file, [&](const std::string& t) { sm::tools::write_disparity_file(t, df); });
  if (camera) depth.write(outs, df, sm::tools::to_mat(res.rl), *camera);
  if (!conf_png.empty())
    outs.write(conf_png, [&](const std::string& t) { sm::tools::write_image_atomic(t, sm::tools::out_to_conf(word)); });
  if (!objects_json.empty()) {
    json j = {{"too_many_objects", res.objects.too_many_objects},
              {"table_full", res.objects.table_full},
              {"labels_started", res.objects.labels_started},
              {"labels_peak", res.objects.labels_peak},
              {"notes", sm::tools::object_flag_lines(sm::object_packet(res.objects, false)[0], hw, r)}};
    j["objects"] = json::array();
    for (const auto& o : res.objects.objects) {
      json b = sm::tools::object_box_json(o);
      b.update(json{{"count", o.count}, {"max_disp", o.max_disp}});
      j["objects"].push_back(b);
    }
    outs.write(objects_json, [&](const std::string& t) { sm::tools::write_text_atomic(t, j.dump(2) + "\n"); });
  }
  outs.commit();
  if (verbose) {
    double total = 0;
    fmt::print("stereo_model: {}x{} DISP {} CENSUS {} SW {}\n", L.w, L.h, hw.disp, hw.census, hw.sw);
    for (const auto& [name, ms] : res.stage_ms) {
      fmt::print("  {:<12} {:9.1f} ms\n", name, ms);
      total += ms;
    }
    fmt::print("  {:<12} {:9.1f} ms\n", "total", total);
    long valid = 0;
    if (mode == "integer")
      for (auto p : d.px) valid += sm::disp_valid(p);
    else
      for (auto w : word.px) valid += sm::out_valid(w);
    std::string files;
    for (const auto* f :
         {&out, &colour, &disp_file, &objects_json, &conf_png, &depth.depth_file, &depth.cloud, &depth.cloud_view})
      if (!f->empty()) files += (files.empty() ? "" : ", ") + *f;
    fmt::print("  {} valid pixels of {}, {} objects -> {}\n", valid, d.px.size(), res.objects.objects.size(), files);
    if (speckle.on()) fmt::print("  host: {} of them cleared as {}\n", speckled, speckle.describe());
    if (mode != "integer") fmt::print("  {}\n", sm::tools::fail_counts_line(sm::tools::fail_counts(word)));
    fmt::print("  labels: {} started, at most {} in use at once (LABEL_SLOTS {})\n", res.objects.labels_started,
               res.objects.labels_peak, hw.label_slots);
    for (const std::string& l : sm::tools::object_flag_lines(sm::object_packet(res.objects, false)[0], hw, r))
      fmt::print("  {}\n", l);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("stereo_model", run, argc, argv); }
