// The prefault hook (core/huge_pages.hpp, app/prefault.hpp): a very large block allocated through
// malloc_advised is faulted in by another thread without being touched by the test, what the owner
// writes meanwhile is kept, and a block below the threshold is left alone.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "app/prefault.hpp"
#include "core/huge_pages.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace prefault_test {

#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
// The share of the whole pages of [p, p + bytes) that are resident (mincore).
double resident_share(void* p, std::size_t bytes) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto begin = (reinterpret_cast<std::uintptr_t>(p) + page - 1) & ~(page - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(page - 1);
  std::vector<unsigned char> in((end - begin) / page);
  if (mincore(reinterpret_cast<void*>(begin), end - begin, in.data()) != 0) return -1.0;
  std::size_t n = 0;
  for (const unsigned char c : in) n += c & 1;
  return static_cast<double>(n) / static_cast<double>(in.size());
}

TEST(Prefault, AVeryLargeBlockIsFaultedInByAnotherThreadAndKeepsWhatIsWritten) {
  beamfea::app::install_background_prefault();
  const std::size_t bytes = beamfea::kPrefaultMinBytes;
  auto* block = static_cast<unsigned char*>(beamfea::malloc_advised(bytes));
  ASSERT_NE(block, nullptr);
  // The owner writes its first and last megabytes while the other thread populates.
  std::memset(block, 0xA5, std::size_t{1} << 20);
  std::memset(block + bytes - (std::size_t{1} << 20), 0x5A, std::size_t{1} << 20);
  double share = 0.0;
  for (int k = 0; k < 200 && share < 0.99; ++k) {  // up to 10 s: 256 MB take well under 1 s here
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    share = resident_share(block, bytes);
  }
  EXPECT_GE(share, 0.99);
  for (std::size_t i = 0; i < (std::size_t{1} << 20); i += 4093) {
    ASSERT_EQ(block[i], 0xA5) << i;
    ASSERT_EQ(block[bytes - 1 - i], 0x5A) << i;
  }
  EXPECT_EQ(block[bytes / 2], 0);  // a populated page the owner never wrote reads zero
  std::free(block);
  beamfea::set_prefault_hook(nullptr);
}

TEST(Prefault, ABlockBelowTheThresholdIsLeftToItsOwner) {
  beamfea::app::install_background_prefault();
  const std::size_t bytes = beamfea::kPrefaultMinBytes / 4;  // 64 MB: glibc maps it fresh
  void* block = beamfea::malloc_advised(bytes);
  ASSERT_NE(block, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_LT(resident_share(block, bytes), 0.5);
  std::free(block);
  beamfea::set_prefault_hook(nullptr);
}
#endif

}  // namespace prefault_test
