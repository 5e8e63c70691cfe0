// Strict reading of the JSON files the tools take (register files, synthesis reports,
// the register map): exactly one JSON value per file, no key twice in one object (the
// JSON grammar allows it and nlohmann-json keeps the last one silently), and a one-line
// error naming the file for a missing, unreadable or malformed file. Header-only
// (nlohmann-json and fmt) for the tools that do not link sm_toolio. docs/robustness.md.
#pragma once

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sm::tools {

struct JsonFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

namespace detail {

// nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 5: ..." without
// the bracketed id.
inline std::string json_error_text(const std::string& what) {
  const size_t b = what.find("] ");
  return what[0] == '[' && b != std::string::npos ? what.substr(b + 2) : what;
}

}  // namespace detail

// Parses `text` (the contents of `path`, named in the errors): one JSON value, then only
// white space; no object with the same key twice. Throws JsonFileError:
//   "<path>: malformed JSON: parse error at line L, column C: ..."
//   "<path>: content after the JSON value on line L (one value per file)"
//   "<path>: key 'occ' given twice in one object"
inline nlohmann::json parse_json_strict(const std::string& text, const std::string& path) {
  // The keys of every object being parsed, innermost last (a stack rather than the
  // callback's depth: object_start reports the parent's depth, key the object's).
  std::vector<std::set<std::string>> open;
  const nlohmann::json::parser_callback_t unique_keys = [&](int, nlohmann::json::parse_event_t ev, nlohmann::json& v) {
    using E = nlohmann::json::parse_event_t;
    if (ev == E::object_start) {
      open.emplace_back();
    } else if (ev == E::object_end) {
      if (!open.empty()) open.pop_back();
    } else if (ev == E::key && !open.empty()) {
      const std::string k = v.get<std::string>();
      if (!open.back().insert(k).second)
        throw JsonFileError(fmt::format("{}: key '{}' given twice in one object", path, k));
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, unique_keys, /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const nlohmann::json::parse_error& e) {
    std::string msg = detail::json_error_text(e.what());
    if (msg.find("; expected end of input") != std::string::npos) {
      // "parse error at line L, column C: ..." -> "line L"
      const size_t at = msg.find("line "), comma = msg.find(',', at);
      const std::string line = at == std::string::npos ? "" : " on " + msg.substr(at, comma - at);
      throw JsonFileError(fmt::format("{}: content after the JSON value{} (one value per file)", path, line));
    }
    throw JsonFileError(fmt::format("{}: malformed JSON: {}", path, msg));
  }
}

// The whole file, checked first: "<path>: no such file", "<path>: is a directory",
// "<path>: cannot read: <reason>".
inline std::string read_text_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw JsonFileError(fmt::format("{}: no such file", path));
  if (fs::is_directory(st)) throw JsonFileError(fmt::format("{}: is a directory", path));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw JsonFileError(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) throw JsonFileError(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
  return ss.str();
}

// read_text_file + parse_json_strict.
inline nlohmann::json read_json_file(const std::string& path) { return parse_json_strict(read_text_file(path), path); }

}  // namespace sm::tools
