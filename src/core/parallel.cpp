#include "mtacc/core/parallel.hpp"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace mtacc {

int threadCount(int threads) {
  // Asked once: the C library reads /sys each time, which costs more than a small batch.
  static const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return threads > 0 ? threads : cores;
}

void parallelFor(long n, int threads, const std::function<void(long, long)>& body, long minimumPerThread) {
  const int t = static_cast<int>(std::min<long>(threadCount(threads), std::max(1L, n / std::max(1L, minimumPerThread))));
  if (t <= 1) {
    body(0, n);
    return;
  }
  const long chunk = (n + t - 1) / t;
  // One slot per chunk: an exception escaping a thread would end the process.
  std::vector<std::exception_ptr> failures(static_cast<size_t>(t));
  auto run = [&](int i) {
    const long begin = i * chunk, end = std::min(n, begin + chunk);
    if (begin >= end) return;
    try {
      body(begin, end);
    } catch (...) {
      failures[static_cast<size_t>(i)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < t; ++i) pool.emplace_back(run, i);
  run(0);
  for (auto& th : pool) th.join();
  for (const auto& failure : failures)
    if (failure) std::rethrow_exception(failure);
}

}  // namespace mtacc
