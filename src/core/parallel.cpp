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

void parallelFor(long n, int threads, const std::function<void(long, long)>& body) {
  const int t = static_cast<int>(std::min<long>(threadCount(threads), std::max(1L, n / 256)));
  if (t <= 1) {
    body(0, n);
    return;
  }
  std::vector<std::thread> pool;
  const long chunk = (n + t - 1) / t;
  for (int i = 1; i < t; ++i) {
    const long begin = i * chunk;
    const long end = std::min(n, begin + chunk);
    if (begin < end) pool.emplace_back(body, begin, end);
  }
  std::exception_ptr failure;
  try {
    body(0, std::min(n, chunk));
  } catch (...) {
    failure = std::current_exception();
  }
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace mtacc
