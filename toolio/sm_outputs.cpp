#include "sm_outputs.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "sm_io.hpp"
#include "sm_signal_cleanup.hpp"

namespace fs = std::filesystem;

namespace sm::tools {

namespace {

// Why a new file cannot be made in `dir` (an existing folder), or "" when it can: a
// probe file is created and removed again (access() would let root pass a read-only folder).
std::string probe_folder(const fs::path& dir) {
  const fs::path probe = dir / fmt::format(".sm_probe{}", getpid());
  const RemoveOnSignal on_signal(probe.string());  // a signal between open and unlink
  const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) return fmt::format("{}: {}", dir.string(), std::strerror(errno));
  close(fd);
  unlink(probe.c_str());
  return {};
}

// Why a file cannot be made in folder `dir` (created if missing when create), or "".
std::string folder_problem(fs::path dir, bool create) {
  std::error_code ec;
  if (dir.empty()) dir = ".";
  const fs::path wanted = dir;
  if (!create && !fs::exists(dir, ec)) return fmt::format("folder {} does not exist", dir.string());
  while (create && !fs::exists(dir, ec) && dir.has_parent_path() && dir.parent_path() != dir) dir = dir.parent_path();
  if (!fs::exists(dir, ec)) dir = ".";
  if (!fs::is_directory(dir, ec)) return fmt::format("{} is not a folder", dir.string());
  const std::string why = probe_folder(dir);
  // a folder still to be created: name it, not only the ancestor the probe ran in
  return why.empty() || dir == wanted ? why : fmt::format("cannot create {} in {}", wanted.string(), why);
}

// Why file `path` cannot be written, or "".
std::string output_problem(const std::string& path, bool create_parent) {
  std::error_code ec;
  const fs::path p(path);
  if (p.filename().empty() || fs::is_directory(p, ec)) return "is a folder";
  return folder_problem(p.parent_path(), create_parent);
}

fs::path absolute_path(const std::string& path) {
  std::error_code ec;
  return fs::weakly_canonical(fs::absolute(path), ec);
}

}  // namespace

void check_outputs(const PathList& outputs, bool create_parent, const PathList& inputs) {
  std::vector<fs::path> read;  // the inputs' absolute paths, once ("" for an empty one)
  for (const auto& in : inputs) read.push_back(in.second.empty() ? fs::path() : absolute_path(in.second));
  std::vector<std::pair<std::string, fs::path>> seen;  // option, absolute path
  for (const auto& [opt, path] : outputs) {
    if (path.empty()) continue;
    const std::string why = output_problem(path, create_parent);
    if (!why.empty()) throw ToolError(fmt::format("{} {}: cannot write: {}", opt, path, why));
    const fs::path abs = absolute_path(path);
    for (const auto& [o, a] : seen)
      if (a == abs) throw ToolError(fmt::format("{} {}: same file as {}", opt, path, o));
    for (size_t i = 0; i < inputs.size(); ++i)
      if (read[i] == abs)
        throw ToolError(
            fmt::format("{} {}: same file as the input {} {}", opt, path, inputs[i].first, inputs[i].second));
    seen.emplace_back(opt, abs);
  }
}

void check_output_folder(const std::string& option, const std::string& dir, const PathList& files) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw ToolError(fmt::format("{} {}: cannot write: not a folder", option, dir));
  const std::string why = folder_problem(dir, true);
  if (!why.empty()) throw ToolError(fmt::format("{} {}: cannot write: {}", option, dir, why));
  for (const auto& [o, f] : files)
    if (!f.empty() && absolute_path(f) == absolute_path(dir))
      throw ToolError(fmt::format("{} {}: same path as {}", option, dir, o));
}

OutputSet::~OutputSet() {
  if (!committed_) discard();
}

std::string OutputSet::stage(const std::string& path, bool create_parent) {
  const fs::path p(path);
  const fs::path dir = p.parent_path();
  std::error_code ec;
  if (create_parent && !dir.empty() && !fs::is_directory(dir, ec)) {
    // Remember every level this call creates, outermost first, to undo them.
    std::vector<fs::path> missing;
    for (fs::path d = dir; !d.empty() && !fs::exists(d, ec); d = d.parent_path()) missing.push_back(d);
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
      for (const auto& d : missing) fs::remove(d, ec);
      throw ToolError(fmt::format("{}: cannot create directory", dir.string()));
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      created_dirs_.push_back(it->string());
      created_dirs_on_signal_.push_back(signal_cleanup_add(it->string(), true));
    }
  }
  const std::string temp =
      (dir / fmt::format(".{}.tmp{}-{}{}", p.stem().string(), getpid(), entries_.size(), p.extension().string()))
          .string();
  entries_.push_back({path, temp, signal_cleanup_add(temp)});
  return temp;
}

void OutputSet::write(const std::string& path, const std::function<void(const std::string&)>& writer,
                      bool create_parent) {
  const std::string temp = stage(path, create_parent);
  try {
    writer(temp);
  } catch (const std::exception& e) {
    std::string msg = e.what();
    for (size_t at = msg.find(temp); at != std::string::npos; at = msg.find(temp, at + path.size()))
      msg.replace(at, temp.size(), path);
    if (msg.find(path) == std::string::npos) msg = fmt::format("{}: {}", path, msg);
    const size_t nl = msg.find('\n');  // one line
    throw ToolError(msg.substr(0, nl));
  }
}

void OutputSet::commit() {
  std::error_code ec;
  for (const auto& e : entries_)
    if (!fs::is_regular_file(e.temp, ec)) {
      discard();
      throw ToolError(fmt::format("{}: cannot write", e.target));
    }
  for (size_t i = 0; i < entries_.size(); ++i) {
    fs::rename(entries_[i].temp, entries_[i].target, ec);
    if (ec) {
      const std::string target = entries_[i].target;
      for (size_t k = 0; k < i; ++k) fs::remove(entries_[k].target, ec);
      discard();
      throw ToolError(fmt::format("{}: cannot write", target));
    }
  }
  committed_ = true;
  forget_on_signal();
}

void OutputSet::discard() noexcept {
  std::error_code ec;
  for (const auto& e : entries_) fs::remove(e.temp, ec);
  // Innermost first; a folder that is not empty (someone else's file) stays.
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) fs::remove(*it, ec);
  forget_on_signal();
  entries_.clear();
  created_dirs_.clear();
}

void OutputSet::forget_on_signal() noexcept {
  for (auto& e : entries_) {
    signal_cleanup_remove(e.on_signal);
    e.on_signal = -1;
  }
  for (int h : created_dirs_on_signal_) signal_cleanup_remove(h);
  created_dirs_on_signal_.clear();
}

}  // namespace sm::tools
