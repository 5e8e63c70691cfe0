// sm_ref_frames: what an external test bench (tests/cocotb) needs to drive sm_top and
// check it, computed by the project's own code: the host's AXI4-Lite register writes
// for a register file (sim/sm_regs_io.hpp, as stereo_sim writes them), the camera words
// of every frame ({right, left} per pixel), and the reference model's output for it
// (model/pipeline.hpp): the disparity words of m_axis and the object packet of
// m_axis_obj (model object_packet). One JSON file, so the bench re-implements nothing.
//
//   sm_ref_frames --regs REGS.json --out REF.json LEFT0 RIGHT0 [LEFT1 RIGHT1 ...]
//
// REGS.json is the register file of stereo_model --regs (toolio/sm_regs_json.hpp),
// compile-time keys included (max_width ... rect_radius: the configuration the bench
// verilates). Every frame uses the same registers; WIDTH x HEIGHT default to the size of
// the first pair; grids are the identity unless the file names a calibration.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calib_file.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_outputs.hpp"
#include "toolio/sm_regs_json.hpp"
#include "pipeline.hpp"
#include "post.hpp"
#include "sm_regmap.hpp"
#include "sm_regs_io.hpp"

namespace {

using json = nlohmann::json;
using sm::tools::ToolError;

int run(int argc, char** argv) {
  std::string regs_path, out;
  std::vector<std::string> images;
  CLI::App app{"Register writes, camera words and reference-model outputs of sm_top for N frames (JSON)"};
  app.add_option("--regs", regs_path, "register file (stereo_model --regs), compile-time keys included")->required();
  app.add_option("-o,--out", out, "output JSON")->required();
  app.add_option("pairs", images, "LEFT RIGHT image pairs, one per frame")->required();
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  if (images.size() % 2 != 0) throw ToolError("images come in LEFT RIGHT pairs");

  sm::tools::quiet_opencv();
  std::vector<std::pair<sm::Image8, sm::Image8>> pairs;
  for (size_t i = 0; i < images.size(); i += 2) {
    pairs.emplace_back(sm::tools::load_grey(images[i]), sm::tools::load_grey(images[i + 1]));
    const auto& [l, r] = pairs.back();
    if (l.w != r.w || l.h != r.h) throw ToolError(fmt::format("{}: size differs from {}", images[i + 1], images[i]));
    if (l.w != pairs[0].first.w || l.h != pairs[0].first.h)
      throw ToolError(fmt::format("{}: size differs from the first frame's", images[i]));
  }

  sm::HwConfig hw;
  sm::Regs r = sm::Regs::defaults(hw);
  sm::tools::RegsFile rf;
  {
    // compile-time keys first (they set the register ranges), then the defaults at that
    // configuration, then the file's registers
    sm::Regs scratch = r;
    rf = sm::tools::apply_regs_json(regs_path, hw, scratch);
    r = sm::Regs::defaults(hw);
    r.width = pairs[0].first.w;
    r.height = pairs[0].first.h;
    sm::tools::apply_regs_json(regs_path, hw, r);
  }
  if (r.width != pairs[0].first.w || r.height != pairs[0].first.h)
    throw ToolError(fmt::format("{}: WIDTH x HEIGHT {}x{} differ from the images' {}x{}", regs_path, r.width, r.height,
                                pairs[0].first.w, pairs[0].first.h));
  r.grid_l = sm::RectGrid::identity(r.width, r.height);
  r.grid_r = r.grid_l;
  if (!rf.calib.empty()) {
    // a rig whose line-buffer radius this IP cannot hold is refused, as by stereo_sim
    try {
      sm::apply_calib(sm::load_fitting_calib(rf.calib, hw), r);
    } catch (const ToolError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw ToolError(e.what());
    }
  }
  try {
    hw.validate();
    sm::validate_regs(r, hw);
  } catch (const std::invalid_argument& e) {
    throw ToolError(fmt::format("{}: {}", regs_path, e.what()));
  }

  json j;
  j["generator"] = "sm_ref_frames";
  j["hw"] = hw.parameters();
  j["width"] = r.width;
  j["height"] = r.height;
  namespace rm = sm::regmap;
  j["addr"] = {{"ID", rm::kID},
               {"CONTROL", rm::kCONTROL},
               {"STATUS", rm::kSTATUS},
               {"ERR_FLAGS", rm::kERR_FLAGS},
               {"ERR_CNT_LINE", rm::kERR_CNT_LINE},
               {"ERR_CNT_SOF", rm::kERR_CNT_SOF},
               {"ERR_CNT_ROWS", rm::kERR_CNT_ROWS},
               {"ERR_CNT_OUT", rm::kERR_CNT_OUT},
               {"CAPS0", rm::kCAPS0},
               {"CAPS1", rm::kCAPS1},
               {"OBJ_HEADER", rm::obj_header_addr()}};
  // read-only registers with a fixed value at this configuration: their fields' reset
  // values from the register map (rtl/regmap.json, parameters evaluated for hw)
  const auto fixed_word = [&](const char* name) {
    for (const auto& reg : rm::registers()) {
      if (std::string(reg.name) != name) continue;
      uint32_t word = 0;
      for (int i = 0; i < reg.num_fields; ++i) {
        const auto& f = rm::fields()[static_cast<size_t>(reg.first_field + i)];
        word |= (static_cast<uint32_t>(f.reset.eval(hw)) << f.lsb) & f.mask();
      }
      return word;
    }
    throw std::logic_error(std::string("register map has no ") + name);
  };
  j["expect"] = {{"ID", fixed_word("ID")}, {"CAPS0", fixed_word("CAPS0")}, {"CAPS1", fixed_word("CAPS1")}};
  // the host's writes, in stereo_sim's order (sm::write_registers, grids into bank 0)
  json writes = json::array();
  for (const sm::RegWord& w : sm::register_words(r))
    writes.push_back({{"addr", w.addr}, {"value", w.value}, {"name", w.name}});
  for (int cam = 0; cam < 2; ++cam)
    for (const auto& [addr, word] : sm::grid_words(hw, cam, 0, cam ? r.grid_r : r.grid_l))
      writes.push_back({{"addr", addr}, {"value", word}, {"name", cam ? "GRID_R" : "GRID_L"}});
  writes.push_back({{"addr", rm::kCONTROL}, {"value", sm::control_word(0)}, {"name", "CONTROL"}});
  j["writes"] = writes;

  j["frames"] = json::array();
  for (const auto& [left, right] : pairs) {
    const sm::PipelineResult res = sm::run_pipeline(left, right, hw, r, false);
    std::vector<uint32_t> cam(left.px.size());
    for (size_t i = 0; i < cam.size(); ++i) cam[i] = static_cast<uint32_t>(right.px[i]) << 8 | left.px[i];
    j["frames"].push_back({{"camera", cam},
                           {"disp", res.out.px},  // the 32-bit output words
                           {"packet", sm::object_packet(res.objects, false)},
                           {"objects", res.objects.objects.size()}});
  }
  sm::tools::OutputSet outs;
  outs.write(out, [&](const std::string& t) { sm::tools::write_text_atomic(t, j.dump() + "\n"); });
  outs.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("sm_ref_frames", run, argc, argv); }
