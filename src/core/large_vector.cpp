#include "mtacc/core/large_vector.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <limits>

namespace mtacc {
namespace {

constexpr std::size_t kHugePage = kLargeBlockBytes;  // the threshold is one huge page

std::size_t mappedBytes(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

}  // namespace

void* allocateLargeBlock(std::size_t bytes) {
  if (bytes > std::numeric_limits<std::size_t>::max() - 2 * kHugePage) throw std::bad_alloc();  // no room to round up
  const std::size_t size = mappedBytes(bytes);
  // One huge page more than needed, then the unaligned head and the rest of the tail given back.
  void* mapped = ::mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > start) ::munmap(mapped, aligned - start);
  const std::uintptr_t end = start + size + kHugePage;
  if (end > aligned + size) ::munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
  auto* block = reinterpret_cast<void*>(aligned);
#ifdef MADV_HUGEPAGE
  ::madvise(block, size, MADV_HUGEPAGE);  // advice only: a kernel without huge pages maps 4 KB ones
#endif
  return block;
}

void freeLargeBlock(void* block, std::size_t bytes) { ::munmap(block, mappedBytes(bytes)); }

}  // namespace mtacc
