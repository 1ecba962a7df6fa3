#include "core/huge_pages.hpp"

#include <atomic>
#include <cstdint>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace beamfea {

namespace {
std::atomic<PrefaultHook> g_prefault{nullptr};
std::atomic<bool> g_advise{true};

// Huge-page advice, then the prefault hook for a very large block.
void advise(void* p, std::size_t bytes) noexcept {
  advise_huge_pages(p, bytes);
  if (p && bytes >= kPrefaultMinBytes)
    if (const PrefaultHook hook = g_prefault.load(std::memory_order_acquire)) hook(p, bytes);
}
}  // namespace

void set_prefault_hook(PrefaultHook hook) noexcept { g_prefault.store(hook, std::memory_order_release); }

void set_huge_page_advice(bool on) noexcept { g_advise.store(on, std::memory_order_relaxed); }
bool huge_page_advice() noexcept { return g_advise.load(std::memory_order_relaxed); }

void advise_huge_pages(void* data, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (!data || bytes < kHugePageMinBytes || !huge_page_advice()) return;
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
  advise(p, bytes);
  return p;
}

void* calloc_advised(std::size_t count, std::size_t size) noexcept {
  void* p = std::calloc(count, size);
  // calloc has already written zeros into reused heap memory; a fresh mapping it leaves untouched.
  if (p && size != 0 && count <= SIZE_MAX / size) advise(p, count * size);
  return p;
}

void* realloc_advised(void* block, std::size_t bytes) noexcept {
  void* p = std::realloc(block, bytes);
  advise(p, bytes);
  return p;
}

}  // namespace beamfea
