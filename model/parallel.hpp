// Row parallelism of the model (--threads): a frame's rows split into contiguous bands,
// one thread per band. Each band's output rows are computed by the same code as in a
// single-thread run, so the result does not depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sm {

// The number of bands parallel_bands uses for n rows: threads clamped to 1..n.
inline int band_count(int n, int threads) { return std::max(1, std::min(threads, n)); }

namespace detail {

// True while the current thread runs a band (a call of parallel_bands inside a band
// then starts its own threads instead of waiting for the pool it is part of).
inline thread_local bool in_band = false;

// Worker threads kept for the life of the process, so that a frame's dozen
// parallel_bands calls (every stage) wake sleeping threads instead of creating and
// joining new ones. One call at a time uses the pool; a concurrent call from another
// thread, or a nested one, gets threads of its own.
class BandPool {
 public:
  ~BandPool() {
    {
      std::lock_guard<std::mutex> g(m_);
      stop_ = true;
      gen_.fetch_add(1, std::memory_order_release);
    }
    work_.notify_all();
    for (auto& t : workers_) t.join();
  }
  // Makes sure there are n - 1 workers and has them poll for a job (a sleeping thread
  // takes long to wake: its wake-up then overlaps the caller's serial work before its
  // next run). Nothing when the caller is in a band.
  void wake(int n) {
    if (in_band) return;
    {
      std::lock_guard<std::mutex> g(m_);
      while (static_cast<int>(workers_.size()) < n - 1) workers_.emplace_back([this] { serve(); });
      gen_.fetch_add(1, std::memory_order_release);
    }
    work_.notify_all();
  }
  // Runs job(b) for b = 0..n-1, band 0 on the calling thread, and returns when all have
  // finished; false (nothing run) when the pool is busy or the caller is in a band.
  bool run(int n, const std::function<void(int)>& job) {
    if (in_band) return false;
    std::unique_lock<std::mutex> busy(run_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> g(m_);
      while (static_cast<int>(workers_.size()) < n - 1) workers_.emplace_back([this] { serve(); });
      job_ = &job;
      next_ = 1;
      count_ = n;
      pending_ = n - 1;
      gen_.fetch_add(1, std::memory_order_release);
    }
    work_.notify_all();
    run_band(job, 0);
    spin_while([this] { return pending_.load(std::memory_order_acquire) != 0; });
    std::unique_lock<std::mutex> g(m_);
    done_.wait(g, [this] { return pending_ == 0; });
    job_ = nullptr;
    return true;
  }

 private:
  static void run_band(const std::function<void(int)>& job, int b) {
    in_band = true;
    job(b);
    in_band = false;
  }
  // Speed: a frame makes a dozen calls in quick succession, and waking a sleeping thread
  // takes tens of microseconds (more in a virtual machine): a worker that has finished its
  // band, and the caller waiting for the bands, first poll for up to kSpinUs, yielding the
  // processor at every poll (so a loaded machine loses nothing), then sleep as before.
  static constexpr int kSpinUs = 200;
  template <class Busy>
  static void spin_while(Busy busy) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinUs);
    while (busy() && std::chrono::steady_clock::now() < end) std::this_thread::yield();
  }
  // Takes bands while there are any; otherwise polls, then sleeps until something is
  // posted (a job, a wake-up, stop: each bumps gen_ under m_). A wake-up without a job
  // starts a new poll.
  void serve() {
    std::unique_lock<std::mutex> g(m_);
    for (;;) {
      if (stop_) return;
      if (job_ && next_ < count_) {
        const int b = next_++;
        const std::function<void(int)>& job = *job_;
        g.unlock();
        run_band(job, b);
        g.lock();
        if (--pending_ == 0) done_.notify_one();
        continue;
      }
      const unsigned seen = gen_.load(std::memory_order_acquire);
      g.unlock();
      spin_while([this, seen] { return gen_.load(std::memory_order_acquire) == seen; });
      g.lock();
      work_.wait(g, [this, seen] { return gen_.load(std::memory_order_acquire) != seen; });
    }
  }
  std::mutex run_, m_;
  std::condition_variable work_, done_;
  std::vector<std::thread> workers_;
  const std::function<void(int)>* job_ = nullptr;
  int next_ = 0, count_ = 0;
  std::atomic<int> pending_{0};   // (written under m_; read by the caller's poll)
  std::atomic<unsigned> gen_{0};  // jobs posted (and stop): what a polling worker watches
  bool stop_ = false;
};

inline BandPool& band_pool() {
  static BandPool pool;
  return pool;
}

}  // namespace detail

// Before a frame's first parallel_bands call: wakes the pool's threads that call will use
// (see BandPool::wake), so that the caller's serial work hides their wake-up.
inline void prepare_bands(int n, int threads) {
  const int t = band_count(n, threads);
  if (t > 1) detail::band_pool().wake(t);
}

// Calls f(begin, end, band) for band = 0..band_count(n, threads)-1 on rows [begin, end),
// which cover 0..n-1 in order; band 0 runs on the calling thread, the others on the
// pool's threads (detail::BandPool; new threads when it is busy). The first exception a
// band throws is rethrown after every band has finished.
template <class F>
void parallel_bands(int n, int threads, F&& f) {
  const int t = band_count(n, threads);
  auto lo = [n, t](int b) { return static_cast<int>(static_cast<long long>(n) * b / t); };
  if (t == 1) {
    f(0, n, 0);
    return;
  }
  std::vector<std::exception_ptr> err(static_cast<size_t>(t));
  const std::function<void(int)> run = [&](int b) {
    try {
      f(lo(b), lo(b + 1), b);
    } catch (...) {
      err[static_cast<size_t>(b)] = std::current_exception();
    }
  };
  if (!detail::band_pool().run(t, run)) {
    std::vector<std::thread> own;
    for (int b = 1; b < t; ++b) own.emplace_back(run, b);
    run(0);
    for (auto& th : own) th.join();
  }
  for (auto& e : err)
    if (e) std::rethrow_exception(e);
}

}  // namespace sm
