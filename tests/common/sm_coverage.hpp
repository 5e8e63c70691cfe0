// Coverage builds (-DSM_COVERAGE=ON, docs/verification.md "Coverage"): a test bench keeps
// one CoverageOnExit per Verilated model, declared after the model so that it goes out of
// scope first: it writes the model context's line and toggle coverage, one point per
// instance, to the file that ctest names in SM_COVERAGE_FILE (<build>/coverage/<test>.dat).
// The counters live in the model, so the data must be written while the model exists. A
// second context of the same process writes <test>.2.dat, and so on. Without SM_COVERAGE
// (the default build) or without SM_COVERAGE_FILE in the environment it does nothing.
#pragma once

#include <verilated.h>

#if defined(SM_COVERAGE) && SM_COVERAGE
#include <cstdlib>
#include <fstream>
#include <string>

#include <verilated_cov.h>
#endif

namespace sm {

class CoverageOnExit {
 public:
  explicit CoverageOnExit(VerilatedContext* ctx) : ctx_(ctx) {}
  ~CoverageOnExit() { write(); }
  CoverageOnExit(const CoverageOnExit&) = delete;
  CoverageOnExit& operator=(const CoverageOnExit&) = delete;

  // Writes the data now (once); the destructor then writes nothing.
  void write() {
#if defined(SM_COVERAGE) && SM_COVERAGE
    if (!ctx_) return;
    const char* env = std::getenv("SM_COVERAGE_FILE");
    if (env && *env) {
      // The first free name of <test>.dat, <test>.2.dat, ...: a second model in this
      // process, or another process of the same test (a test that runs stereo_sim
      // several times), must not overwrite the data already written.
      std::string path = env;
      const auto dot = path.rfind(".dat");
      const std::string stem = dot == std::string::npos ? path : path.substr(0, dot);
      for (int n = 2; std::ifstream(path).good(); ++n) path = stem + "." + std::to_string(n) + ".dat";
      // one point per instance (not summed over a model's instances): a toggle point is
      // covered when one instance saw both edges (tools/sm_coverage.cpp)
      ctx_->coveragep()->forcePerInstance(true);
      // silently: a tool run with -q prints nothing (test_sim_depth checks it, coverage
      // builds included)
      ctx_->coveragep()->write(path.c_str());
    }
#endif
    ctx_ = nullptr;
  }

 private:
  VerilatedContext* ctx_;
};

}  // namespace sm
