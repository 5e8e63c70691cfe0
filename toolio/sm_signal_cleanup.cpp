#include "sm_signal_cleanup.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace sm::tools {

namespace {

// The registry is a fixed table of slots holding heap copies of the paths, so that the
// handler never allocates or locks: a slot's path pointer is published with release
// order and taken back (set to null) before its string is freed. Registrations beyond
// the table's size are not covered (a tool keeps a few dozen temporaries at a time).
constexpr int kSlots = 4096;
struct Slot {
  std::atomic<char*> path{nullptr};
  std::atomic<bool> is_dir{false};
  std::atomic<bool> used{false};
};
std::array<Slot, kSlots> g_slots;
std::mutex g_add_mutex;  // registration only (never taken by the handler)
struct sigaction g_old_int, g_old_term;

void remove_all() {
  // Files first, then folders from the most recent registration backwards (inner
  // folders are registered after the folders that hold them).
  for (auto& s : g_slots)
    if (char* p = s.path.load(std::memory_order_acquire); p && !s.is_dir.load()) unlink(p);
  for (int i = kSlots - 1; i >= 0; --i)
    if (char* p = g_slots[i].path.load(std::memory_order_acquire); p && g_slots[i].is_dir.load()) rmdir(p);
}

void on_signal(int sig) {
  remove_all();
  const struct sigaction& old = sig == SIGINT ? g_old_int : g_old_term;
  if (old.sa_handler == SIG_DFL || old.sa_handler == SIG_IGN || (old.sa_flags & SA_SIGINFO)) {
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, nullptr);
    raise(sig);  // delivered when this handler returns: the process ends with `sig`
  } else {
    old.sa_handler(sig);
  }
}

// Installs on_signal for SIGINT and SIGTERM unless it is in place already, keeping the
// action it replaces (checked at every registration, as a library may have replaced it).
void install_handlers() {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction cur {};
    sigaction(sig, nullptr, &cur);
    if (!(cur.sa_flags & SA_SIGINFO) && (cur.sa_handler == on_signal || cur.sa_handler == SIG_IGN))
      continue;  // ours, or ignored (e.g. a background job): leave it
    (sig == SIGINT ? g_old_int : g_old_term) = cur;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace

int signal_cleanup_add(const std::string& path, bool is_dir) {
  std::lock_guard<std::mutex> lock(g_add_mutex);
  install_handlers();
  for (int i = 0; i < kSlots; ++i) {
    Slot& s = g_slots[i];
    if (s.used.load()) continue;
    s.used.store(true);
    s.is_dir.store(is_dir);
    s.path.store(strdup(path.c_str()), std::memory_order_release);
    return i;
  }
  return -1;
}

void signal_cleanup_remove(int handle) noexcept {
  if (handle < 0 || handle >= kSlots) return;
  Slot& s = g_slots[handle];
  std::free(s.path.exchange(nullptr, std::memory_order_acq_rel));
  std::lock_guard<std::mutex> lock(g_add_mutex);
  s.used.store(false);
}

}  // namespace sm::tools
