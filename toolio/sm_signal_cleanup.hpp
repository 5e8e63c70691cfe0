// Temporary files and folders that must not outlive an interrupted tool: paths registered
// here are removed when the process receives SIGINT or SIGTERM (Ctrl-C, kill), after
// which the signal's previous action runs (by default the process ends with that
// signal). The handler only calls async-signal-safe functions (unlink, rmdir, sigaction,
// raise). OutputSet and write_image_atomic / write_text_atomic register their
// temporaries; a harness registers its own (e.g. a partial VCD) with a RemoveOnSignal.
#pragma once

#include <string>

namespace sm::tools {

// Registers `path` (a file, or with `is_dir` an empty folder) for removal on SIGINT /
// SIGTERM and installs the handlers on first use (a signal whose action is SIG_IGN is
// left alone). Returns a handle for signal_cleanup_remove.
int signal_cleanup_add(const std::string& path, bool is_dir = false);
// Forgets a registration (the path itself is not touched); -1 is ignored.
void signal_cleanup_remove(int handle) noexcept;

// RAII form: registered from construction until release() or destruction.
class RemoveOnSignal {
 public:
  RemoveOnSignal() = default;
  explicit RemoveOnSignal(const std::string& path, bool is_dir = false) : h_(signal_cleanup_add(path, is_dir)) {}
  ~RemoveOnSignal() { release(); }
  RemoveOnSignal(RemoveOnSignal&& o) noexcept : h_(o.h_) { o.h_ = -1; }
  RemoveOnSignal& operator=(RemoveOnSignal&& o) noexcept {
    if (this != &o) {
      release();
      h_ = o.h_;
      o.h_ = -1;
    }
    return *this;
  }
  RemoveOnSignal(const RemoveOnSignal&) = delete;
  RemoveOnSignal& operator=(const RemoveOnSignal&) = delete;
  void release() noexcept {
    signal_cleanup_remove(h_);
    h_ = -1;
  }

 private:
  int h_ = -1;
};

}  // namespace sm::tools
