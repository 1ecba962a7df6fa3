#include "app/huge_pages_policy.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <strings.h>
#include <exception>
#include <system_error>

#include "core/huge_pages.hpp"

namespace beamfea::app {

namespace {

constexpr int kHugePageOrder = 9;          // 2 MiB = 2^9 pages of 4 KiB
constexpr std::size_t kReportingBit = 5;  // VIRTIO_BALLOON_F_REPORTING (virtio spec 5.5.3)

bool one_of(const char* v, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (strcasecmp(v, w) == 0) return true;
  return false;
}

}  // namespace

HugePageChoice choose_huge_pages(const char* env, std::optional<int> reporting_order,
                                 const std::vector<std::string>& balloon_features) {
  if (env && one_of(env, {"1", "on", "yes"})) return {true, "advised (BEAMFEA_HUGE_PAGES)"};
  if (env && one_of(env, {"0", "off", "no"})) return {false, "not advised (BEAMFEA_HUGE_PAGES)"};
  bool reporting = false;
  for (const std::string& f : balloon_features)
    if (f.size() > kReportingBit && f[kReportingBit] == '1') reporting = true;
  if (reporting && reporting_order && *reporting_order <= kHugePageOrder)
    return {false, "not advised: the host takes back free 2 MiB blocks (free page reporting); BEAMFEA_HUGE_PAGES=1 advises them"};
  return {true, "advised (transparent huge pages for large buffers)"};
}

HugePageChoice configure_huge_pages() {
  std::optional<int> order;
  if (std::ifstream in("/sys/module/page_reporting/parameters/page_reporting_order"); in) {
    int o = 0;
    if (in >> o) order = o;
  }
  std::vector<std::string> features;
  try {
    std::error_code ec;
    for (const auto& d : std::filesystem::directory_iterator("/sys/bus/virtio/drivers/virtio_balloon", ec)) {
      std::ifstream in(d.path() / "features");  // the driver's bind/unbind files have none
      std::string f;
      if (in >> f) features.push_back(f);
    }
  } catch (const std::exception&) {
    // Unreadable: as without a balloon.
  }
  HugePageChoice c = choose_huge_pages(std::getenv("BEAMFEA_HUGE_PAGES"), order, features);
  set_huge_page_advice(c.advise);
  return c;
}

}  // namespace beamfea::app
