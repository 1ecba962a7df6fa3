#pragma once
// Transparent huge pages for large buffers.
//
// A buffer's pages are given to the process when first touched, one fault per 4 KiB page: at
// 21,504 DOFs `beamfea run` touches about 240 MB that way (the factor, the assembly's triplets,
// the element matrices), some 60,000 faults and 14 % of its time (perf, docs/performance.md).
// Linux gives 2 MiB pages instead to the ranges a program marks with madvise(MADV_HUGEPAGE) when
// the system's transparent huge pages are in "madvise" mode (Debian's default; in "always" mode it
// does so unasked, in "never" mode not at all): one fault per 2 MiB. Measured here: touching 200 MB
// takes 90 ms in 4 KiB pages and 30 ms in huge pages.
#include <cstddef>

namespace beamfea {

// Buffers below this size are not advised: a huge page is only given for a whole aligned 2 MiB
// inside the buffer, and a small buffer's pages are mostly reused heap pages already.
inline constexpr std::size_t kHugePageMinBytes = std::size_t{4} << 20;

// Advises the kernel to back the 2 MiB-aligned part of [data, data + bytes) with huge pages when
// it is first touched (not const: the memory is not read, and may be uninitialised). Advice only: nothing below kHugePageMinBytes, nothing outside Linux, and a
// refusal (huge pages off) is ignored. Call it before the buffer is first written.
void advise_huge_pages(void* data, std::size_t bytes) noexcept;

// std::malloc, std::calloc and std::realloc, each followed by advise_huge_pages on the new block:
// the allocation functions given to a C library that allocates its large arrays itself (CHOLMOD,
// solvers/sparse_factor.cpp). Freed with std::free.
void* malloc_advised(std::size_t bytes) noexcept;
void* calloc_advised(std::size_t count, std::size_t size) noexcept;
void* realloc_advised(void* block, std::size_t bytes) noexcept;

}  // namespace beamfea
