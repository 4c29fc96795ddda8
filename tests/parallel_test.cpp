#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mtacc/core/parallel.hpp"

namespace mtacc {
namespace {

std::vector<std::pair<long, long>> chunks(long n, int threads, long minimumPerThread) {
  std::mutex m;
  std::vector<std::pair<long, long>> seen;
  parallelFor(n, threads, [&](long begin, long end) {
    const std::lock_guard lock(m);
    seen.emplace_back(begin, end);
  }, minimumPerThread);
  std::sort(seen.begin(), seen.end());
  return seen;
}

TEST(ParallelFor, HeavyItemsAreSplitEvenWhenFew) {
  // Eight layers of a grid, three threads: a thread for every three layers, all covered once.
  EXPECT_EQ(chunks(8, 3, 1), (std::vector<std::pair<long, long>>{{0, 3}, {3, 6}, {6, 8}}));
  // Light items: a thread only for 256 of them, so eight stay on the calling thread.
  EXPECT_EQ(chunks(8, 3, 256), (std::vector<std::pair<long, long>>{{0, 8}}));
  EXPECT_EQ(chunks(600, 3, 256), (std::vector<std::pair<long, long>>{{0, 300}, {300, 600}}));
}

TEST(ParallelFor, AChunksExceptionReachesTheCallerAfterTheJoin) {
  EXPECT_THROW(parallelFor(4, 2, [](long begin, long) {
    if (begin > 0) throw std::runtime_error("second chunk");
  }, 1), std::runtime_error);
}

}  // namespace
}  // namespace mtacc
