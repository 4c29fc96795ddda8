#pragma once
// Parallel loops. One threads policy for the whole library: a `threads` argument of 0 means
// every core of the machine (kAllCores), a positive number that many threads; every public
// function that takes one defaults to kAllCores. Results never depend on the thread count.
#include <functional>

namespace mtacc {

constexpr int kAllCores = 0;

// The number of threads `threads` stands for (kAllCores: the hardware concurrency, at least 1).
int threadCount(int threads);

// Runs body(begin, end) over [0, n) split into contiguous chunks, one per thread; the calling
// thread takes the first chunk. An exception of any chunk (the first in order) is rethrown after
// every thread joined.
// A thread is started only for at least `minimumPerThread` items: starting one costs tens of
// microseconds, more than a few hundred light items (a pose's kinematics); a caller whose items
// are heavy (a layer of a grid, an eigenproblem) passes 1.
void parallelFor(long n, int threads, const std::function<void(long, long)>& body, long minimumPerThread = 256);

}  // namespace mtacc
