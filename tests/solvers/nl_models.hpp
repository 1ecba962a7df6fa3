#pragma once
// Small models for the buckling and path-following tests, written as input JSON.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/model_reader.hpp"

namespace beamfea::test {

using json = nlohmann::json;

// A straight member along x from (0,0,0) to (L,0,0) in n elements; orientation z (local y = global y).
inline json straight_member(double L, int n, double E, double G, double A, double Iy, double Iz, double J) {
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L, 0, 0}}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", E}, {"G", G}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}}});
  d["elements"] = json::array({{{"id", "bar"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"},
                                {"section", "s"}, {"orientation", {0, 0, 1}}, {"divisions", n}}});
  d["supports"] = json::array();
  d["loads"] = json::array();
  return d;
}

// "N3" from ("N", 3), without operator+ on a literal (a GCC 12 -Wrestrict false positive).
inline std::string name(const char* prefix, int i) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s%d", prefix, i);
  return std::string(buf);
}

inline json fix(const std::string& node, std::initializer_list<const char*> dofs) {
  json a = json::array();
  for (const char* d : dofs) a.push_back(d);
  return {{"node", node}, {"fix", a}};
}

inline json load(const std::string& node, double fx, double fy, double fz, double mx = 0, double my = 0, double mz = 0) {
  return {{"node", node}, {"force", {fx, fy, fz}}, {"moment", {mx, my, mz}}};
}

// A planar chain of n rigid links of length L along x, joined by revolute springs about z of
// stiffness k (the first joint at the fixed base), Pashkevich's lumped model of a straight link.
inline json rigid_chain(int n, double L, double k) {
  json d;
  d["nodes"] = json::array();
  d["elements"] = json::array();
  d["joints"] = json::array();
  for (int i = 0; i <= n; ++i) {
    d["nodes"].push_back({{"id", name("N", i)}, {"xyz", {i * L, 0, 0}}});
    if (i < n) d["nodes"].push_back({{"id", name("J", i)}, {"xyz", {i * L, 0, 0}}});
  }
  for (int i = 0; i < n; ++i) {
    d["joints"].push_back({{"id", name("q", i)}, {"type", "revolute"},
                           {"nodes", {name("N", i), name("J", i)}},
                           {"axes", {{0, 0, 1}}}, {"stiffness", {k}}});
    d["elements"].push_back({{"id", name("L", i)}, {"type", "rigid"},
                             {"nodes", {name("J", i), name("N", i + 1)}}});
  }
  d["supports"] = json::array({fix("N0", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array();
  return d;
}

}  // namespace beamfea::test
