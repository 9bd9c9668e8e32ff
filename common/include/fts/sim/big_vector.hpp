// Vectors for the physics' per-ball working memory, which asks the kernel for 2 MiB
// pages. At 10^5 balls the continuous model's buffers span thousands of 4 KiB pages,
// more than the TLB maps, and its scattered accesses (a collision touches the balls
// around it) then pay a page walk each — in a virtual machine a two-level one. Debian's
// kernels back memory with huge pages where a program asks (transparent_hugepage =
// madvise); a vector of at least kBigBytes asks, smaller ones are plain allocations.
// Only speed depends on it: no result does (BENCHMARKS.md, issue 18).
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace fts::sim {

namespace detail {
inline constexpr std::size_t kBigBytes = std::size_t{1} << 20;
void* allocate_big(std::size_t bytes, std::size_t alignment);
void free_big(void* p, std::size_t bytes, std::size_t alignment) noexcept;
}  // namespace detail

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(detail::allocate_big(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { detail::free_big(p, n * sizeof(T), alignof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using BigVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace fts::sim
