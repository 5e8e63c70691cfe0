// Lower-case text for names and file extensions: register and parameter names (the C++
// member and tool option of DISP is disp), and extensions compared whatever their case
// (.PNG is .png). Header-only, so the code generator that runs before the model is built
// uses it too.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace sm {

inline std::string lower_case(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The path's extension with its dot, lower-cased ("" when it has none).
inline std::string lower_extension(const std::string& path) {
  return lower_case(std::filesystem::path(path).extension().string());
}

}  // namespace sm
