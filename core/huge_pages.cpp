#include "core/huge_pages.hpp"

#include <cstdint>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace beamfea {

namespace {
constexpr std::uintptr_t kHugePageBytes = std::uintptr_t{2} << 20;  // x86-64 and arm64 (4 KiB base pages)
}  // namespace

void advise_huge_pages(void* data, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (!data || bytes < kHugePageMinBytes) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHugePageBytes - 1);
  if (last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

void* malloc_advised(std::size_t bytes) noexcept {
  void* p = std::malloc(bytes);
  advise_huge_pages(p, bytes);
  return p;
}

void* calloc_advised(std::size_t count, std::size_t size) noexcept {
  void* p = std::calloc(count, size);
  // calloc has already written zeros into reused heap memory; a fresh mapping it leaves untouched.
  if (p && size != 0 && count <= SIZE_MAX / size) advise_huge_pages(p, count * size);
  return p;
}

void* realloc_advised(void* block, std::size_t bytes) noexcept {
  void* p = std::realloc(block, bytes);
  advise_huge_pages(p, bytes);
  return p;
}

}  // namespace beamfea
