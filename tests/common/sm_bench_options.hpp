// The command line of a Verilated block test (sm_block_test.hpp): the kernel's own
// options and the bench's knobs. CLI11 parses it, but only in sm_bench_options.cpp,
// compiled once into sm_bench_options: CLI11 is header-only and cost about 5 s of
// compile time in every one of the ~90 bench objects, a third of the suite's build.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class Option;
}

namespace sm::test {

// One option, to refine after adding it (each call returns the option again).
class BenchOption {
 public:
  explicit BenchOption(CLI::Option* opt) : opt_(opt) {}
  BenchOption& required();
  // lo <= value <= hi (each element of a list option).
  BenchOption& range(long long lo, long long hi);
  // A list option also splits its values at this character ("--widths 17,32").
  BenchOption& delimiter(char c);
  // A string option: one of these words.
  BenchOption& one_of(const std::vector<std::string>& words);
  // An integer option given by name: "--filter med3" stores names.at("med3").
  BenchOption& names(const std::map<std::string, int>& names);

 private:
  CLI::Option* opt_;
};

class BenchOptions {
 public:
  explicit BenchOptions(const std::string& description);
  ~BenchOptions();
  BenchOptions(const BenchOptions&) = delete;
  BenchOptions& operator=(const BenchOptions&) = delete;

  BenchOption option(const std::string& name, int& v, const std::string& help);
  BenchOption option(const std::string& name, long& v, const std::string& help);
  BenchOption option(const std::string& name, unsigned& v, const std::string& help);
  BenchOption option(const std::string& name, double& v, const std::string& help);
  BenchOption option(const std::string& name, std::string& v, const std::string& help);
  BenchOption option(const std::string& name, std::vector<int>& v, const std::string& help);
  BenchOption flag(const std::string& name, bool& v, const std::string& help);

  // Parses argv. Returns the exit code when the program must stop here (--help: 0, a bad
  // option: its message and CLI11's code), nothing when the bench goes on.
  std::optional<int> parse(int argc, char** argv);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sm::test
