// When the program advises huge pages (app/huge_pages_policy.hpp): the rule on what the system
// says, and the program's setting applied to core/huge_pages.
#include "app/huge_pages_policy.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include "core/huge_pages.hpp"

namespace huge_pages_policy_test {

using beamfea::app::choose_huge_pages;

namespace {
// Feature bits as /sys prints them: bit 0 first. Bit 5 is VIRTIO_BALLOON_F_REPORTING; this one is
// the balloon of the machine measured in docs/performance.md (stats queue, deflate on OOM,
// reporting, ...).
const std::string kReporting = "0110010100000000000000000000000010000000";
const std::string kNoReporting = "0110000100000000000000000000000010000000";
}  // namespace

TEST(HugePagesPolicy, FreePageReportingOfHugePagesTurnsTheAdviceOff) {
  EXPECT_FALSE(choose_huge_pages(nullptr, 9, {kReporting}).advise);   // 2 MiB blocks reported
  EXPECT_FALSE(choose_huge_pages(nullptr, 0, {kReporting}).advise);   // any block reported
  EXPECT_FALSE(choose_huge_pages(nullptr, 9, {kNoReporting, kReporting}).advise);
}

TEST(HugePagesPolicy, OtherwiseHugePagesAreAdvised) {
  EXPECT_TRUE(choose_huge_pages(nullptr, std::nullopt, {}).advise);         // bare metal
  EXPECT_TRUE(choose_huge_pages(nullptr, 9, {}).advise);                    // reporting built in, no balloon
  EXPECT_TRUE(choose_huge_pages(nullptr, 9, {kNoReporting}).advise);        // a balloon that does not report
  EXPECT_TRUE(choose_huge_pages(nullptr, 10, {kReporting}).advise);         // only 4 MiB blocks and larger
  EXPECT_TRUE(choose_huge_pages(nullptr, std::nullopt, {kReporting}).advise);
  EXPECT_TRUE(choose_huge_pages(nullptr, 9, {"01100"}).advise);             // too short to have bit 5
}

TEST(HugePagesPolicy, TheVariableDecides) {
  for (const char* on : {"1", "on", "YES"}) EXPECT_TRUE(choose_huge_pages(on, 9, {kReporting}).advise) << on;
  for (const char* off : {"0", "Off", "no"}) EXPECT_FALSE(choose_huge_pages(off, std::nullopt, {}).advise) << off;
  // Anything else: as if unset.
  EXPECT_FALSE(choose_huge_pages("maybe", 9, {kReporting}).advise);
  EXPECT_TRUE(choose_huge_pages("", std::nullopt, {}).advise);
  EXPECT_NE(choose_huge_pages("0", 9, {kReporting}).reason.find("BEAMFEA_HUGE_PAGES"), std::string::npos);
}

TEST(HugePagesPolicy, TheProgramsChoiceIsApplied) {
  const char* set = std::getenv("BEAMFEA_HUGE_PAGES");
  const std::string saved = set ? set : "";
  setenv("BEAMFEA_HUGE_PAGES", "0", 1);
  EXPECT_FALSE(beamfea::app::configure_huge_pages().advise);
  EXPECT_FALSE(beamfea::huge_page_advice());
  setenv("BEAMFEA_HUGE_PAGES", "1", 1);
  EXPECT_TRUE(beamfea::app::configure_huge_pages().advise);
  EXPECT_TRUE(beamfea::huge_page_advice());
  if (set) setenv("BEAMFEA_HUGE_PAGES", saved.c_str(), 1);
  else unsetenv("BEAMFEA_HUGE_PAGES");
  beamfea::set_huge_page_advice(true);
}

}  // namespace huge_pages_policy_test
