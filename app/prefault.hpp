#pragma once
// Very large fresh blocks faulted in on a thread of their own (core/huge_pages.hpp: the prefault
// hook). The program (the CLI) installs it once at start.
#include <cstddef>

namespace beamfea::app {

// Faults [data, data + bytes) in, writable, 2 MiB at a time, on a detached thread started for it,
// with madvise(MADV_POPULATE_WRITE) (Linux 5.14): pages already present, and what was written into
// them, are left as they are, so the block's owner may write into it meanwhile. It stops at the
// first refusal (an older kernel, a block freed meanwhile); a thread that cannot be started does
// nothing. Elsewhere than Linux: nothing.
void prefault_in_background(void* data, std::size_t bytes) noexcept;

// set_prefault_hook(prefault_in_background).
void install_background_prefault() noexcept;

}  // namespace beamfea::app
