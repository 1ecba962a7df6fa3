// core/huge_pages.hpp: huge-page advice for large buffers, and the allocation functions given to
// CHOLMOD. What must hold: the advice marks a large block's 2 MiB-aligned part for huge pages
// (Linux, transparent huge pages in "madvise" mode: the kernel's /proc/self/smaps then says
// "THPeligible: 1" for it, Documentation/admin-guide/mm/transhuge.rst), a block without advice is
// not marked (other modes: as the test says), and the functions behave as malloc, calloc and realloc. That CHOLMOD allocates
// through them: tests/solvers/cholmod_allocation_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "core/huge_pages.hpp"

namespace huge_pages_test {

using namespace beamfea;

namespace {

// The system's mode: "always", "madvise" or "never" (the bracketed word), empty if unknown.
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(in, line)) return {};
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? std::string() : line.substr(open + 1, close - open - 1);
}

// The THPeligible flag of the mapping that holds `address`, from /proc/self/smaps (none: unknown).
std::optional<int> thp_eligible(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream in("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-' && line.find(':') > line.find(' ')) {
      inside = lo <= a && a < hi;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return std::nullopt;
}

constexpr std::size_t kBlock = std::size_t{16} << 20;  // four times kHugePageMinBytes
constexpr std::uintptr_t kTwoMiB = std::uintptr_t{2} << 20;

const char* middle_page(const void* block) {  // inside the aligned part of a kBlock block
  const auto a = (reinterpret_cast<std::uintptr_t>(block) + kTwoMiB - 1) & ~(kTwoMiB - 1);
  return reinterpret_cast<const char*>(a + kTwoMiB);
}

}  // namespace

// Each mode of the system's setting has its outcome: "madvise" (Debian's default) marks the advised
// block and not the plain one; "always" marks both; "never" neither, advice or not. The mode file
// and the smaps line exist on every Linux this project builds on (THPeligible since 5.0).
TEST(HugePages, AdviceMarksALargeBlockAsTheSystemsModeSays) {
  const std::string mode = thp_mode();
  ASSERT_TRUE(mode == "madvise" || mode == "always" || mode == "never") << "mode '" << mode << "'";
  void* plain = std::malloc(kBlock);
  void* advised = malloc_advised(kBlock);
  ASSERT_TRUE(plain && advised);
  const auto plain_flag = thp_eligible(middle_page(plain));
  const auto advised_flag = thp_eligible(middle_page(advised));
  std::free(plain);
  std::free(advised);
  ASSERT_TRUE(plain_flag && advised_flag) << "no THPeligible line in /proc/self/smaps";
  EXPECT_EQ(*advised_flag, mode == "never" ? 0 : 1) << mode;
  EXPECT_EQ(*plain_flag, mode == "always" ? 1 : 0) << mode;
}

TEST(HugePages, NoBlockIsAdvisedWhileTheAdviceIsOff) {
  // The program turns the advice off on a machine whose host takes free huge pages back
  // (app/huge_pages_policy.hpp): an advised block is then a plain one, in every mode but "always".
  const std::string mode = thp_mode();
  ASSERT_TRUE(huge_page_advice());  // the default
  set_huge_page_advice(false);
  void* advised = malloc_advised(kBlock);
  ASSERT_NE(advised, nullptr);
  const auto flag = thp_eligible(middle_page(advised));
  std::free(advised);
  set_huge_page_advice(true);
  ASSERT_TRUE(flag) << "no THPeligible line in /proc/self/smaps";
  EXPECT_EQ(*flag, mode == "always" ? 1 : 0) << mode;
}

TEST(HugePages, TheAllocationFunctionsBehaveAsTheCLibrarys) {
  auto* z = static_cast<unsigned char*>(calloc_advised(kBlock, 1));
  ASSERT_NE(z, nullptr);
  bool zero = true;
  for (std::size_t i = 0; i < kBlock; i += 4093) zero = zero && z[i] == 0;
  EXPECT_TRUE(zero);
  std::memset(z, 7, 1000);
  auto* r = static_cast<unsigned char*>(realloc_advised(z, 2 * kBlock));  // the first bytes kept
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r[0], 7);
  EXPECT_EQ(r[999], 7);
  std::free(r);
  // (calloc's own overflow check is the C library's: under AddressSanitizer an overflowing
  // count * size is a reported error, not a null return, so it is not exercised here.)
  void* small = malloc_advised(100);  // below kHugePageMinBytes: plain malloc
  ASSERT_NE(small, nullptr);
  std::free(small);
  advise_huge_pages(nullptr, kBlock);  // nothing to advise: no effect
}

}  // namespace huge_pages_test
