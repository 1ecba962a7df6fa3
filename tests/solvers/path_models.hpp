#pragma once
// The classic snap-through benchmarks of path following, as users write them (a reference load P,
// planar: out-of-plane DOFs held at every node).
#include <cmath>
#include <numbers>

#include "nl_models.hpp"

namespace beamfea::test {

// Planar frame helpers: every node holds uz, rx, ry.
inline void hold_out_of_plane(json& d) {
  for (const auto& n : d["nodes"]) d["supports"].push_back(fix(n["id"].get<std::string>(), {"uz", "rx", "ry"}));
}

// Deep circular arch (Da Deppo & Schmidt 1975; Simo & Vu-Quoc 1986 sec. 7.2): radius R = 100,
// opening 215 deg, hinged at the left end, clamped at the right, point load P at the apex; EI = 1e6,
// EA = 1e10 (nearly inextensional). Node "apex" is n/2 (n even). Published limit load P R^2 / EI = 8.97
// (P = 897).
inline json deep_arch(int n, double P, double EA = 1e10) {
  const double R = 100.0, pi = 3.14159265358979323846, half = 107.5 * pi / 180.0;
  json d;
  d["nodes"] = json::array();
  d["elements"] = json::array();
  d["supports"] = json::array();
  for (int i = 0; i <= n; ++i) {
    const double t = -half + 2 * half * i / n;
    d["nodes"].push_back({{"id", i == n / 2 ? std::string("apex") : name("n", i)}, {"xyz", {R * std::sin(t), R * std::cos(t), 0}}});
  }
  auto id = [&](int i) { return i == n / 2 ? std::string("apex") : name("n", i); };
  for (int i = 0; i < n; ++i)
    d["elements"].push_back({{"id", name("e", i)}, {"type", "beam"}, {"nodes", {id(i), id(i + 1)}}, {"material", "m"},
                             {"section", "s"}, {"orientation", {0, 0, 1}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", 1e6}, {"G", 4e5}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", EA / 1e6}, {"Iy", 1.0}, {"Iz", 1.0}, {"J", 1.0}}});
  hold_out_of_plane(d);
  d["supports"].push_back(fix(id(0), {"ux", "uy"}));
  d["supports"].push_back(fix(id(n), {"ux", "uy", "rz"}));
  d["loads"] = json::array({load("apex", 0, -P, 0)});
  return d;
}

// Lee's frame (Lee, Manuel & Rossow 1968) with the data of Schweizerhof & Wriggers (1986): E = 7.2e6,
// A = 6, I = 2, L = 120, the load P from the corner at 24, pinned ends, 10 + 2 + 8 elements. First
// limit load 1.85e4 (P L^2 / EI = 18.5).
inline json lees_frame(double P) {
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "C"}, {"xyz", {0, 120, 0}}},
                            {{"id", "P"}, {"xyz", {24, 120, 0}}}, {{"id", "B"}, {"xyz", {120, 120, 0}}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", 7.2e6}, {"G", 2.769e6}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", 6.0}, {"Iy", 200.0}, {"Iz", 2.0}, {"J", 200.0}}});
  d["elements"] = json::array({{{"id", "col"}, {"type", "beam"}, {"nodes", {"A", "C"}}, {"material", "m"}, {"section", "s"},
                                {"orientation", {0, 0, 1}}, {"divisions", 10}},
                               {{"id", "b1"}, {"type", "beam"}, {"nodes", {"C", "P"}}, {"material", "m"}, {"section", "s"},
                                {"orientation", {0, 0, 1}}, {"divisions", 2}},
                               {{"id", "b2"}, {"type", "beam"}, {"nodes", {"P", "B"}}, {"material", "m"}, {"section", "s"},
                                {"orientation", {0, 0, 1}}, {"divisions", 8}}});
  d["supports"] = json::array({fix("A", {"ux", "uy", "uz", "rx", "ry"}), fix("B", {"ux", "uy", "uz", "rx", "ry"})});
  d["loads"] = json::array({load("P", 0, -P, 0)});
  return d;
}

// Williams' toggle (Williams 1964): two members clamped at the ends, half-span a = 12.943 in, rise
// h = 0.386 in, E = 10.3e6 psi, b x d = 0.753 x 0.243 in (A = 0.18298 in^2, I = 9.0040e-4 in^4),
// load P at the apex; `per_member` elements per member.
inline json williams_toggle(int per_member, double P) {
  const double a = 12.943, h = 0.386, b = 0.753, t = 0.243;
  json d;
  d["nodes"] = json::array({{{"id", "L"}, {"xyz", {-a, 0, 0}}}, {{"id", "apex"}, {"xyz", {0, h, 0}}},
                            {{"id", "R"}, {"xyz", {a, 0, 0}}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", 10.3e6}, {"G", 3.96e6}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", b * t}, {"Iy", t * b * b * b / 12}, {"Iz", b * t * t * t / 12}, {"J", 1.0}}});
  d["elements"] = json::array({{{"id", "left"}, {"type", "beam"}, {"nodes", {"L", "apex"}}, {"material", "m"}, {"section", "s"},
                                {"orientation", {0, 0, 1}}, {"divisions", per_member}},
                               {{"id", "right"}, {"type", "beam"}, {"nodes", {"apex", "R"}}, {"material", "m"}, {"section", "s"},
                                {"orientation", {0, 0, 1}}, {"divisions", per_member}}});
  d["supports"] = json::array({fix("L", {"ux", "uy", "uz", "rx", "ry", "rz"}), fix("R", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array({load("apex", 0, -P, 0)});
  return d;
}

// A cantilever A-B of 20 elements (EA = 1e4, EI = GJ = EI) fixed at A, with the end moment
// M = 2 pi EI / L about z at B that rolls it into a full circle (Simo & Vu-Quoc 1986; Battini &
// Pacoste 2002): the tip returns to the root, R = I.
inline json rolled_cantilever(double L, double EI) {
  json d = straight_member(L, 20, 1.0, 1.0, 1e4, EI, EI, EI);
  d["materials"][0]["E"] = 1.0;
  d["materials"][0]["G"] = 1.0;
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 0, 0, 0, 0, 0, 2 * std::numbers::pi * EI / L));
  return d;
}

}  // namespace beamfea::test
