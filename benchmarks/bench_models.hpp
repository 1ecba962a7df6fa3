#pragma once
// Models shared by the small-model benchmarks (bench_sweep_rate, bench_small_models), as JSON
// documents written the way users write them.
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

namespace beamfea::bench {

using json = nlohmann::json;

inline json material_and_section() {
  return {{"materials", {json{{"id", "al"}, {"E", 70e9}, {"nu", 0.33}}}},
          {"sections", {json{{"id", "link"}, {"shape", "rectangle"}, {"b", 0.02}, {"h", 0.04}}}}};
}

// Three links of 0.3 m, each meshed into 2 elements, joined by revolute joints about z with
// actuator springs; the base joint sits on a clamped ground node. 10 nodes, 60 + 3 DOFs.
inline json chain() {
  json m = material_and_section();
  m["nodes"] = json::array();
  m["elements"] = json::array();
  m["joints"] = json::array();
  m["nodes"].push_back({{"id", "G"}, {"xyz", {0, 0, 0}}});
  std::string prev = "G";
  for (int l = 1; l <= 3; ++l) {
    const double x0 = 0.3 * (l - 1), x1 = 0.3 * l;
    const std::string s = fmt::format("L{}s", l), e = l == 3 ? "T" : fmt::format("L{}e", l);
    m["nodes"].push_back({{"id", s}, {"xyz", {x0, 0, 0}}});
    m["nodes"].push_back({{"id", e}, {"xyz", {x1, 0, 0}}});
    m["joints"].push_back({{"id", fmt::format("q{}", l)}, {"type", "revolute"}, {"nodes", {prev, s}},
                           {"axes", {{0, 0, 1}}}, {"stiffness", {2000.0}}});
    m["elements"].push_back({{"id", fmt::format("link{}", l)}, {"type", "beam"}, {"nodes", {s, e}},
                             {"material", "al"}, {"section", "link"}, {"divisions", 2}});
    prev = e;
  }
  m["supports"] = {json{{"node", "G"}, {"fix", "all"}}};
  m["loads"] = {json{{"node", "T"}, {"force", {0, -10.0, 0}}}};
  m["analyses"] = {json{{"id", "K"}, {"type", "stiffness"}, {"node", "T"}}};
  return m;
}

}  // namespace beamfea::bench
