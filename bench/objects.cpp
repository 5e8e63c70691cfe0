// bench_objects: the objects the scene generator placed against the object list the model
// reports, on --seeds built-in-style scenes (320x240, 128 levels, 6 objects: the built-in
// scene is seed 1), at the paper configuration's defaults, the zynq configuration's (its
// speckle mode: SPECKLE_EN 1, LR_EN 0, AGREE_EN 0), zynq with the per-pixel rules instead
// (SPECKLE_EN 0, LR_EN 1, AGREE_EN 1, the paper's), and the speckle mode with no region
// trusted (SPECKLE_TRUST 4095). An object counts when at least OBJ_MIN_PIXELS of it are
// visible at or above OBJ_NEAR (test_scene's rule); a missed one is listed as
// disparity/visible pixels (matched/kept: the % of them the post filters give its level,
// +-2, and the % the output word keeps valid there; a low matched share is the matcher's
// miss, a high kept share the labeller's). docs/evaluation.md, "Speckles".
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "configs.hpp"
#include "pipeline.hpp"
#include "toolio/sm_cli.hpp"
#include "toolio/sm_io.hpp"
#include "toolio/sm_placed_objects.hpp"

namespace {

struct Mode {
  const char* name;
  bool zynq, pixel_rules, trust;  // pixel_rules: zynq with the paper's checked rules
};
constexpr Mode kModes[] = {{"paper", false, false, true},
                           {"zynq (speckle mode)", true, false, true},
                           {"zynq, per-pixel rules", true, true, true},
                           {"zynq speckle mode, no region trusted", true, false, false}};

// The placed objects that count and are missing from the model's list in `m`.
std::vector<sm::tools::PlacedCheck> missed(const sm::tools::SceneParams& p, const sm::tools::SyntheticScene& s,
                                           const Mode& m, int* counted) {
  const sm::HwConfig hw = sm::named_config(m.zynq ? "zynq" : "paper");
  sm::Regs r = sm::Regs::defaults(hw);
  if (m.pixel_rules) sm::set_checked_rules(r, false);
  if (!m.trust) r.speckle_trust = 4095;
  const sm::PipelineResult res = sm::tools::run_on_scene(p, s, hw, r);
  std::vector<sm::tools::PlacedCheck> out;
  *counted = 0;
  for (const auto& c : sm::tools::check_placed_objects(p, s, res, r.obj_min_pixels, r.obj_near)) {
    *counted += c.counts;
    if (c.counts && !c.found) out.push_back(c);
  }
  return out;
}

std::string list(const std::vector<sm::tools::PlacedCheck>& v) {
  std::string s;
  for (const auto& c : v)
    s += fmt::format("{}{}/{} ({}/{})", s.empty() ? "" : " ", c.obj.disp, c.visible, 100 * c.matched / c.visible,
                     100 * c.kept / c.visible);
  return s.empty() ? "-" : s;
}

int run(int argc, char** argv) {
  int seeds = 10;
  std::string json_path;
  CLI::App app{"objects the scene generator placed, found or missed in the model's object list, per mode"};
  app.add_option("--seeds", seeds, "scenes: seeds 1..N (seed 1: the built-in scene)")
      ->check(sm::tools::int_in(1, 1000))
      ->capture_default_str();
  app.add_option("--json", json_path, "write the table as JSON");
  if (const auto rc = sm::tools::parse_args(app, argc, argv)) return *rc;
  nlohmann::json js;
  std::vector<int> missed_total(std::size(kModes), 0);
  int counted_total = 0;
  fmt::print("| seed | objects that count |");
  for (const Mode& m : kModes) fmt::print(" missed, {} |", m.name);
  fmt::print("\n|---:|---:|");
  for (size_t k = 0; k < std::size(kModes); ++k) fmt::print("---|");
  fmt::print("\n");
  for (int seed = 1; seed <= seeds; ++seed) {
    const sm::tools::SceneParams p = [&] {
      sm::tools::SceneParams q;
      q.seed = static_cast<uint64_t>(seed);
      q.objects = 6;
      return q;
    }();
    const sm::tools::SyntheticScene s = sm::tools::render_scene(p);
    std::string row;
    int counted = 0;
    for (size_t k = 0; k < std::size(kModes); ++k) {
      const auto miss = missed(p, s, kModes[k], &counted);
      missed_total[k] += static_cast<int>(miss.size());
      const std::string cell = list(miss);
      row += fmt::format(" {} |", cell);
      js["seeds"][std::to_string(seed)][kModes[k].name] = cell;
      std::fprintf(stderr, "\rseed %d/%d", seed, seeds);
    }
    counted_total += counted;
    fmt::print("| {} | {} |{}\n", seed, counted, row);
  }
  std::fprintf(stderr, "\n");
  std::string row;
  for (size_t k = 0; k < std::size(kModes); ++k) {
    row += fmt::format(" {} |", missed_total[k]);
    js["missed"][kModes[k].name] = missed_total[k];
  }
  js["counted"] = counted_total;
  fmt::print("| all | {} |{}\n", counted_total, row);
  if (!json_path.empty()) sm::tools::write_text_atomic(json_path, js.dump(2) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return sm::tools::guarded_main("bench_objects", run, argc, argv); }
