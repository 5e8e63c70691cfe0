#include "sm_bench_options.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "toolio/sm_cli.hpp"

namespace sm::test {

BenchOption& BenchOption::required() {
  opt_->required();
  return *this;
}
BenchOption& BenchOption::range(long long lo, long long hi) {
  opt_->check(sm::tools::int_in(lo, hi));
  return *this;
}
BenchOption& BenchOption::delimiter(char c) {
  opt_->delimiter(c);
  return *this;
}
BenchOption& BenchOption::one_of(const std::vector<std::string>& words) {
  opt_->check(CLI::IsMember(words));
  return *this;
}
BenchOption& BenchOption::names(const std::map<std::string, int>& names) {
  opt_->transform(CLI::CheckedTransformer(names));
  return *this;
}

struct BenchOptions::Impl {
  explicit Impl(const std::string& description) : app(description) {}
  CLI::App app;
};

BenchOptions::BenchOptions(const std::string& description) : impl_(std::make_unique<Impl>(description)) {}
BenchOptions::~BenchOptions() = default;

BenchOption BenchOptions::option(const std::string& name, int& v, const std::string& help) {
  return BenchOption(impl_->app.add_option(name, v, help));
}
BenchOption BenchOptions::option(const std::string& name, long& v, const std::string& help) {
  return BenchOption(impl_->app.add_option(name, v, help));
}
BenchOption BenchOptions::option(const std::string& name, unsigned& v, const std::string& help) {
  return BenchOption(impl_->app.add_option(name, v, help));
}
BenchOption BenchOptions::option(const std::string& name, double& v, const std::string& help) {
  return BenchOption(impl_->app.add_option(name, v, help));
}
BenchOption BenchOptions::option(const std::string& name, std::string& v, const std::string& help) {
  return BenchOption(impl_->app.add_option(name, v, help));
}
BenchOption BenchOptions::option(const std::string& name, std::vector<int>& v, const std::string& help) {
  return BenchOption(impl_->app.add_option(name, v, help));
}
BenchOption BenchOptions::flag(const std::string& name, bool& v, const std::string& help) {
  return BenchOption(impl_->app.add_flag(name, v, help));
}

std::optional<int> BenchOptions::parse(int argc, char** argv) {
  try {
    sm::tools::check_delimited(impl_->app, argc, argv);
    impl_->app.parse(argc, argv);
  } catch (const sm::tools::UsageError& e) {
    fmt::print(stderr, "{}\n", e.what());
    return sm::tools::kExitUsage;
  } catch (const CLI::ParseError& e) {
    return impl_->app.exit(e);
  }
  return std::nullopt;
}

}  // namespace sm::test
