#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "mtacc/core/large_vector.hpp"
#include "mtacc/core/transform.hpp"

using namespace mtacc;

TEST(LargeVector, LargeBlocksAreHugePageAlignedAndHoldTheirValues) {
  const size_t n = 150001;  // one feed of seed 004's instrument samples, 3.6 MB of Vec3
  LargeVector<Vec3> series(n);
  ASSERT_GE(n * sizeof(Vec3), kLargeBlockBytes);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(series.data()) % (std::uintptr_t{2} << 20), 0u);
  for (size_t i = 0; i < n; ++i) series[i] = Vec3(static_cast<double>(i), -1.0, 2.0);
  series.resize(3 * n);  // moved to a larger block, the old one released
  EXPECT_EQ(series[n - 1], Vec3(static_cast<double>(n - 1), -1.0, 2.0));
  EXPECT_EQ(series[2 * n], Vec3::Zero());
  LargeVector<Vec3> copy = series;
  EXPECT_EQ(copy, series);
  series.clear();
  series.shrink_to_fit();
  EXPECT_EQ(copy[7], Vec3(7.0, -1.0, 2.0));
}

TEST(LargeVector, SmallBlocksComeFromOperatorNew) {
  LargeVector<double> small(1000);
  std::iota(small.begin(), small.end(), 0.0);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(small.data()) % alignof(double), 0u);
  EXPECT_EQ(small[999], 999.0);
  small.assign(kLargeBlockBytes / sizeof(double), 1.5);  // grows past the threshold
  EXPECT_EQ(small.back(), 1.5);
}

TEST(LargeVector, AnImpossibleSizeThrowsBadAlloc) {
  LargeBlockAllocator<double> allocator;
  EXPECT_THROW((void)allocator.allocate(std::size_t{1} << 60), std::bad_alloc);
  EXPECT_THROW((void)allocator.allocate(std::size_t(-1) / 8 - 1), std::bad_alloc);  // rounding up to 2 MB would wrap
  EXPECT_THROW((void)allocator.allocate(std::size_t(-1) / 4), std::bad_array_new_length);
}

TEST(LargeVector, AFreedBlockIsReusedForTheNextOfItsSizeAndTheKeptBytesAreBounded) {
  const size_t bytes = 3 * kLargeBlockBytes + 5;  // mapped in four huge pages
  void* first = allocateLargeBlock(bytes);
  freeLargeBlock(first, bytes);
  EXPECT_GE(keptLargeBlockBytes(), 4 * kLargeBlockBytes);
  void* other = allocateLargeBlock(kLargeBlockBytes);  // another size: not that block
  EXPECT_NE(other, first);
  void* again = allocateLargeBlock(4 * kLargeBlockBytes);  // the same mapped size
  EXPECT_EQ(again, first);
  static_cast<char*>(again)[4 * kLargeBlockBytes - 1] = 1;  // the whole block is mapped
  freeLargeBlock(again, 4 * kLargeBlockBytes);
  freeLargeBlock(other, kLargeBlockBytes);

  std::vector<void*> many;  // 600 MB mapped (never touched), then freed: at most 512 MB kept
  for (int k = 0; k < 300; ++k) many.push_back(allocateLargeBlock(kLargeBlockBytes));
  for (void* block : many) freeLargeBlock(block, kLargeBlockBytes);
  EXPECT_LE(keptLargeBlockBytes(), std::size_t{512} << 20);
  EXPECT_GE(keptLargeBlockBytes(), std::size_t{500} << 20);
}
