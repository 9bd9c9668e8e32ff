#include "fts/sim/big_vector.hpp"

#include <sys/mman.h>

#include <cstdlib>

namespace fts::sim::detail {
namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
}  // namespace

void* allocate_big(std::size_t bytes, std::size_t alignment) {
  if (bytes < kBigBytes) return ::operator new(bytes, std::align_val_t{alignment});
  // Whole huge pages, aligned to one, so that the kernel can map every byte with them.
  const std::size_t size = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, size);
  if (p == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  madvise(p, size, MADV_HUGEPAGE);  // advice: where it is refused, 4 KiB pages serve
#endif
  return p;
}

void free_big(void* p, std::size_t bytes, std::size_t alignment) noexcept {
  if (bytes < kBigBytes) {
    ::operator delete(p, std::align_val_t{alignment});
  } else {
    std::free(p);
  }
}

}  // namespace fts::sim::detail
