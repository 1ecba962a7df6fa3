#include "app/prefault.hpp"

#include <algorithm>
#include <cstdint>
#include <thread>

#include "core/huge_pages.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace beamfea::app {

void prefault_in_background(void* data, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  constexpr std::uintptr_t kPage = 4096, kStep = kHugePageBytes;  // one huge page per step
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kPage - 1) & ~(kPage - 1);  // madvise wants page-aligned ranges
  const std::uintptr_t last = (begin + bytes) & ~(kPage - 1);
  if (last <= first) return;
  try {
    // In steps, front to back: the owner's first touches also go front to back, and each step
    // that is done before the owner gets there is a fault the owner does not take.
    std::thread([first, last] {
      for (std::uintptr_t a = first; a < last; a += kStep)
        if (madvise(reinterpret_cast<void*>(a), std::min(last, a + kStep) - a, MADV_POPULATE_WRITE) != 0) return;
    }).detach();
  } catch (...) {
    // No thread to be had (std::system_error, or no memory for its state): the owner faults its
    // pages in itself, as without the hook.
  }
#else
  (void)data;
  (void)bytes;
#endif
}

void install_background_prefault() noexcept { set_prefault_hook(&prefault_in_background); }

}  // namespace beamfea::app
