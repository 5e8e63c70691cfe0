// All-or-nothing output files for the command-line tools: every output is first written
// under a temporary name next to its target, and only when all of them are written are
// they renamed into place. A tool that fails half way (exception, error exit) leaves no
// partial output: the temporaries are removed, and so are the folders the set created
// (also on SIGINT / SIGTERM: sm_signal_cleanup.hpp).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace sm::tools {

// Checks, before any work, that every output can be written: (option, path) pairs, empty
// paths skipped. A path must not be a folder, its folder must exist (with create_parent:
// its nearest existing ancestor) and accept a new file (a probe file is created and
// removed), and no two outputs may name the same file. Throws ToolError
// "<option> <path>: cannot write: <reason>" (reason: "folder nodir does not exist",
// "ro: Permission denied", "is a folder", "f is not a folder") or
// "<option> <path>: same file as <other option>". No output may name one of `inputs`, the
// files the tool reads as (option, path): "<option> <path>: same file as the input
// <input option> <input path>".
using PathList = std::vector<std::pair<std::string, std::string>>;
void check_outputs(const PathList& outputs, bool create_parent = false, const PathList& inputs = {});
// The same for an output folder (created by the tool when missing): it, or its nearest
// existing ancestor, is a folder that accepts a new file, and it is not one of the tool's
// output `files` (option, path): "<option> <dir>: same path as <file option>".
void check_output_folder(const std::string& option, const std::string& dir, const PathList& files = {});

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet();  // not committed: removes the temporaries and the folders it created

  // Registers `path` as an output and returns the temporary path to write it to (same
  // folder, same extension, so writers that choose the format by extension still work).
  // With `create_parent`, missing parent folders are created (and removed again unless
  // the set is committed). Throws ToolError when the folder cannot be created.
  std::string stage(const std::string& path, bool create_parent = false);

  // stage(path) and `writer(temporary)`; an exception from the writer is rethrown as a
  // ToolError whose message names `path` instead of the temporary.
  void write(const std::string& path, const std::function<void(const std::string&)>& writer,
             bool create_parent = false);

  // Renames every temporary to its target. Throws ToolError (naming the file) when a
  // temporary is missing or a rename fails; the outputs already renamed are removed.
  void commit();

  // Removes the temporaries and created folders now (also done by the destructor).
  void discard() noexcept;

 private:
  void forget_on_signal() noexcept;  // drops the signal_cleanup registrations
  struct Entry {
    std::string target, temp;
    int on_signal = -1;  // signal_cleanup_add handle of `temp`
  };
  std::vector<Entry> entries_;
  std::vector<std::string> created_dirs_;  // outermost first
  std::vector<int> created_dirs_on_signal_;
  bool committed_ = false;
};

}  // namespace sm::tools
