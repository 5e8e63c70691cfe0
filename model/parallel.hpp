// Row parallelism of the model (--threads): a frame's rows split into contiguous bands,
// one std::thread per band. Each band's output rows are computed by the same code as in
// a single-thread run, so the result does not depend on the thread count.
#pragma once

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace sm {

// The number of bands parallel_bands uses for n rows: threads clamped to 1..n.
inline int band_count(int n, int threads) { return std::max(1, std::min(threads, n)); }

// Calls f(begin, end, band) for band = 0..band_count(n, threads)-1 on rows [begin, end),
// which cover 0..n-1 in order; band 0 runs on the calling thread. The first exception a
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
  auto run = [&](int b) {
    try {
      f(lo(b), lo(b + 1), b);
    } catch (...) {
      err[static_cast<size_t>(b)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int b = 1; b < t; ++b) pool.emplace_back(run, b);
  run(0);
  for (auto& th : pool) th.join();
  for (auto& e : err)
    if (e) std::rethrow_exception(e);
}

}  // namespace sm
