#pragma once
// Storage for long series (a value per instrument sample: hundreds of thousands of rows): a
// std::vector whose large blocks are mapped in 2 MB pages where the kernel has them
// (transparent huge pages, madvise), as NumPy does for its arrays of 4 MB and more. Writing a
// fresh block of 4 KB pages faults once per page, and under a hypervisor a fault costs
// microseconds: 300 MB of series took 0.95 s to touch in 4 KB pages, 0.02 s in huge ones (measured
// on the 2-core CI host). A block is mapped in whole huge pages, so it may hold up to 2 MB more
// than asked (a tenth more for a series of 150,000 points); smaller blocks come from operator new.
// A freed block is kept for the next block of its size, up to 512 MB in all (the kernel would
// zero a fresh one page by page), and given back to the kernel beyond that.
#include <cstddef>
#include <new>
#include <vector>

namespace mtacc {

// Blocks of at least one huge page are mapped on their own, aligned to 2 MB and advised for
// huge pages.
inline constexpr std::size_t kLargeBlockBytes = std::size_t{2} << 20;

void* allocateLargeBlock(std::size_t bytes);          // throws std::bad_alloc
void freeLargeBlock(void* block, std::size_t bytes);  // bytes as allocated
std::size_t keptLargeBlockBytes();                    // freed and kept for reuse, in all

template <class T>
struct LargeBlockAllocator {
  using value_type = T;
  LargeBlockAllocator() = default;
  template <class U>
  explicit LargeBlockAllocator(const LargeBlockAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kLargeBlockBytes) return static_cast<T*>(allocateLargeBlock(bytes));
    return static_cast<T*>(::operator new(bytes, std::align_val_t{alignof(T)}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kLargeBlockBytes) freeLargeBlock(p, bytes);
    else ::operator delete(p, std::align_val_t{alignof(T)});
  }
  template <class U>
  bool operator==(const LargeBlockAllocator<U>&) const noexcept { return true; }
};

template <class T>
using LargeVector = std::vector<T, LargeBlockAllocator<T>>;

}  // namespace mtacc
