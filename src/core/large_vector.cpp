#include "mtacc/core/large_vector.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <limits>
#include <map>
#include <mutex>

namespace mtacc {
namespace {

constexpr std::size_t kHugePage = kLargeBlockBytes;  // the threshold is one huge page

std::size_t mappedBytes(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

// Freed blocks kept for the next block of the same mapped size, up to kKeptBytes in all: the
// kernel zeroes every page it maps afresh (a sixth of the decomposition's time when nothing was
// kept, measured), and glibc's heap keeps what a program frees for the same reason. A kept block
// is advised MADV_FREE: the kernel may take its pages back when memory runs short, and maps a
// page taken back afresh on its next write.
constexpr std::size_t kKeptBytes = std::size_t{512} << 20;
struct KeptBlocks {
  std::mutex mutex;
  std::multimap<std::size_t, void*> bySize;  // mapped bytes -> block
  std::size_t bytes = 0;
};
KeptBlocks& keptBlocks() {
  static auto* kept = new KeptBlocks;  // never destroyed: a LargeVector may outlive any static
  return *kept;
}

void* keptBlock(std::size_t size) {
  KeptBlocks& kept = keptBlocks();
  const std::lock_guard lock(kept.mutex);
  auto found = kept.bySize.upper_bound(size);  // the last kept of this size: the likeliest in the cache
  if (found == kept.bySize.begin() || (--found)->first != size) return nullptr;
  void* block = found->second;
  kept.bySize.erase(found);
  kept.bytes -= size;
  return block;
}

bool keep(void* block, std::size_t size) {
  KeptBlocks& kept = keptBlocks();
  const std::lock_guard lock(kept.mutex);
  if (kept.bytes + size > kKeptBytes) return false;
#ifdef MADV_FREE
  ::madvise(block, size, MADV_FREE);
#endif
  kept.bySize.emplace(size, block);
  kept.bytes += size;
  return true;
}

}  // namespace

void* allocateLargeBlock(std::size_t bytes) {
  if (bytes > std::numeric_limits<std::size_t>::max() - 2 * kHugePage) throw std::bad_alloc();  // no room to round up
  const std::size_t size = mappedBytes(bytes);
  if (void* block = keptBlock(size)) return block;
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

void freeLargeBlock(void* block, std::size_t bytes) {
  const std::size_t size = mappedBytes(bytes);
  if (!keep(block, size)) ::munmap(block, size);
}

std::size_t keptLargeBlockBytes() {
  KeptBlocks& kept = keptBlocks();
  const std::lock_guard lock(kept.mutex);
  return kept.bytes;
}

}  // namespace mtacc
