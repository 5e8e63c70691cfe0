// stereo_sim interrupted (sm_sim_interrupt.hpp).
#include "sm_sim_interrupt.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <initializer_list>

namespace sm::simapp {

namespace {

std::atomic<bool> g_line_open{false};

// Async-signal-safe only: write, sigaction, raise.
void on_signal(int sig) {
  if (g_line_open.load()) {
    const char nl = '\n';
    [[maybe_unused]] const ssize_t n = write(2, &nl, 1);
  }
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);  // delivered when the handler returns: the process ends with `sig`
}

}  // namespace

void end_progress_line_on_signal() {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction cur {};
    sigaction(sig, nullptr, &cur);
    if (!(cur.sa_flags & SA_SIGINFO) && cur.sa_handler == SIG_IGN) continue;  // e.g. a background job
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, nullptr);
  }
}

void set_progress_line_open(bool open) { g_line_open.store(open); }

}  // namespace sm::simapp
