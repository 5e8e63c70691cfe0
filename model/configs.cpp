#include "configs.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

namespace sm {

namespace {

struct Named {
  const char* name;
  std::vector<std::pair<const char*, int>> params;  // sm_top parameter, value
};

const std::vector<Named>& table() {
  static const std::vector<Named> t = {
#include "sm_configs.inc"
  };
  return t;
}

}  // namespace

std::vector<std::string> config_names() {
  std::vector<std::string> names;
  for (const Named& n : table()) names.emplace_back(n.name);
  return names;
}

HwConfig named_config(const std::string& name) {
  for (const Named& n : table()) {
    if (name != n.name) continue;
    HwConfig hw;
    for (const auto& [param, value] : n.params) {
      int* f = hw.field(param);
      if (!f) throw std::logic_error(fmt::format("named_config: {} sets {}, which HwConfig has not", name, param));
      *f = value;
    }
    return hw;
  }
  throw std::invalid_argument(fmt::format("no configuration '{}' (one of {})", name, fmt::join(config_names(), ", ")));
}

}  // namespace sm
