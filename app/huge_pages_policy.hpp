#pragma once
// Whether the large buffers ask for transparent huge pages (core/huge_pages.hpp), decided once by
// the program (the CLI, the Python module) at start.
//
// On an ordinary machine a 2 MiB page costs one fault instead of 512, and the buffers that are
// advised (CHOLMOD's factor, the element matrices, the assembly's triplets) are written whole. On a
// virtual machine whose host takes back the guest's free memory in 2 MiB blocks (virtio-balloon
// free page reporting with page_reporting_order <= 9: Firecracker's and QEMU's "free page
// reporting"), every free huge page of the guest has been handed back to the host, so a huge page
// is one the host must back afresh on its first touch, while the kernel hands 4 KiB pages out of
// its smaller free blocks, which the host still backs. Measured on such a machine (an AMD Zen 5
// guest, docs/performance.md, "Huge pages"): the 97,344-DOF cube's whole process 5.4-5.8 s with huge
// pages against 3.8-4.0 s without, system time 4.5 s against 1.7 s. There the advice is left off.
//
// BEAMFEA_HUGE_PAGES=1 (or on/yes) asks for huge pages whatever the machine, =0 (off/no) never.
#include <optional>
#include <string>
#include <vector>

namespace beamfea::app {

struct HugePageChoice {
  bool advise = true;
  std::string reason;  // one line, for --version and the Python module
};

// The rule, from what the system says:
// `env`: BEAMFEA_HUGE_PAGES's value (null: unset);
// `reporting_order`: /sys/module/page_reporting/parameters/page_reporting_order (none: no free page
//   reporting in the kernel);
// `balloon_features`: the feature bit strings of the virtio balloon devices
//   (/sys/bus/virtio/drivers/virtio_balloon/virtio*/features: one '0' or '1' per bit, bit 0 first);
//   bit 5 is VIRTIO_BALLOON_F_REPORTING.
// Huge pages are advised unless free page reporting is on (a balloon with bit 5, an order of at
// most 9, the order of a 2 MiB page) or the variable says otherwise.
HugePageChoice choose_huge_pages(const char* env, std::optional<int> reporting_order,
                                 const std::vector<std::string>& balloon_features);

// Reads the variable and the system, applies the choice (set_huge_page_advice) and returns it.
// Call once, at start, before any analysis.
HugePageChoice configure_huge_pages();

}  // namespace beamfea::app
