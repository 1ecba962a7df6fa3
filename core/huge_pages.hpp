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

// The huge page size (x86-64 and arm64 with 4 KiB base pages).
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// Buffers below this size are not advised: a huge page is only given for a whole aligned 2 MiB
// inside the buffer, and a small buffer's pages are mostly reused heap pages already.
inline constexpr std::size_t kHugePageMinBytes = std::size_t{4} << 20;

// Whether advise_huge_pages advises at all (true by default). A program may turn the advice off
// once at start, before analyses run: on a virtual machine whose host takes back every free 2 MiB
// block of the guest (free page reporting), a huge page is almost always one the host must back
// afresh, and faulting it costs more than the 4 KiB pages the kernel hands out from its warmer
// small free blocks (app/huge_pages_policy.hpp, docs/performance.md).
void set_huge_page_advice(bool on) noexcept;
bool huge_page_advice() noexcept;

// Advises the kernel to back the 2 MiB-aligned part of [data, data + bytes) with huge pages when
// it is first touched (not const: the memory is not read, and may be uninitialised). Advice only:
// nothing below kHugePageMinBytes, nothing while set_huge_page_advice(false), nothing outside
// Linux, and a refusal (huge pages off) is ignored. Call it before the buffer is first written.
void advise_huge_pages(void* data, std::size_t bytes) noexcept;

// Faulting a very large block in ahead of its use. The kernel zeroes each page at its first
// touch, on the touching thread: CHOLMOD's factor (0.73 GB at 97,344 DOFs) is touched by its
// numeric factorisation supernode by supernode on the main thread, 17 % of a 1e5 run's CPU in
// `clear_page_erms` on the machine measured, while OpenBLAS's worker waits. A program may install
// a hook that faults such a block in on another thread as soon as it is allocated
// (app/prefault.hpp: MADV_POPULATE_WRITE, which changes nothing already written). Threads are the
// program's, so core only calls the hook. Blocks below kPrefaultMinBytes are left alone: at
// 21,504 DOFs (an 83 MB factor, numeric factorisation 0.3 s) the thread cost more than it saved
// (docs/performance.md).
inline constexpr std::size_t kPrefaultMinBytes = std::size_t{256} << 20;
using PrefaultHook = void (*)(void* data, std::size_t bytes) noexcept;
// Sets the hook called by the *_advised functions below for a new block of at least
// kPrefaultMinBytes; null (the default) calls nothing. Set it once, before analyses run.
void set_prefault_hook(PrefaultHook hook) noexcept;

// std::malloc, std::calloc and std::realloc, each followed by advise_huge_pages on the new block
// (and the prefault hook on a very large one): the allocation functions given to a C library that
// allocates its large arrays itself (CHOLMOD, solvers/sparse_factor.cpp). Freed with std::free.
void* malloc_advised(std::size_t bytes) noexcept;
void* calloc_advised(std::size_t count, std::size_t size) noexcept;
void* realloc_advised(void* block, std::size_t bytes) noexcept;

}  // namespace beamfea
