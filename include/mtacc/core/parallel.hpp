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
// thread takes the first chunk. An exception of any chunk is rethrown after every thread joined.
void parallelFor(long n, int threads, const std::function<void(long, long)>& body);

}  // namespace mtacc
