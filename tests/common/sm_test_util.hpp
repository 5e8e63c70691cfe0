// Small helpers the unit and system tests share: a fresh scratch folder and the
// parameters of the synthetic scenes (sm_scene) the tests render.
#pragma once

#include <cstdint>
#include <filesystem>

#include "toolio/sm_scenegen.hpp"

namespace sm::test {

// `dir` as an empty folder (whatever an earlier run left there is removed).
inline std::filesystem::path fresh_dir(const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A width x height scene of `levels` disparity levels with `objects` objects, the rest of
// the parameters at sm_scene's defaults.
inline sm::tools::SceneParams scene_params(int width, int height, int levels, uint64_t seed, int objects) {
  sm::tools::SceneParams p;
  p.width = width;
  p.height = height;
  p.levels = levels;
  p.seed = seed;
  p.objects = objects;
  return p;
}

}  // namespace sm::test
