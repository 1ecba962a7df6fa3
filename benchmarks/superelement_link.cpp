// bench_superelement_link: a link of about 10,000 DOFs condensed onto its two end nodes (a Guyan
// superelement, solvers/superelement.hpp: one factorisation of the interior, 12 solves) against one
// linear static solve of the same link clamped at one end and loaded at the other.
//
// Two links, both written as users write them (JSON read by the model reader):
//   beam     one straight steel tube of 1 m divided into n elements (6 (n + 1) DOFs)
//   lattice  a square lattice girder of 0.1 m x 0.1 m, bays of 0.1 m: four chords, four battens
//            and four face diagonals per bay (tubes), each end joined to a hub node by four spokes
//            (24 DOFs per bay); the hubs are the interface nodes
//
// Timed (thread CPU, paired rounds: benchmarks/bench_timing.hpp), each the whole library call:
//   linear    solve_linear_static of the link with the base hub clamped and a tip force (DofMap,
//             assembly, factorisation, solve, reactions and end forces)
//   condense  reduce_superelement of the free-free link onto {base, tip} (DofMap, assembly,
//             factorisation of the interior, 12 solves, the 12 x 12 K_z and its rigid-body modes;
//             the table says how many it found: 6 expected)
//
// Usage: bench_superelement_link [--dofs 10000] [--budget 6]
// Output: a Markdown table on stdout, progress on stderr.
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "bench_blas.hpp"
#include "bench_timing.hpp"
#include "io/model_reader.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/superelement.hpp"

namespace {

using json = nlohmann::json;

json materials_and_sections() {
  return {{"materials", {json{{"id", "steel"}, {"E", 2.1e11}, {"nu", 0.3}}}},
          {"sections", {json{{"id", "tube"}, {"shape", "tube"}, {"d", 0.02}, {"t", 0.002}},
                        json{{"id", "big"}, {"shape", "tube"}, {"d", 0.06}, {"t", 0.005}}}}};
}

json beam_link(int dofs) {
  json m = materials_and_sections();
  const int n = std::max(1, dofs / 6 - 1);
  m["nodes"] = {json{{"id", "A"}, {"xyz", {0, 0, 0}}}, json{{"id", "B"}, {"xyz", {1.0, 0, 0}}}};
  m["elements"] = {json{{"id", "link"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "steel"},
                        {"section", "big"}, {"orientation", {0, 0, 1}}, {"divisions", n}}};
  return m;
}

json lattice_link(int dofs) {
  json m = materials_and_sections();
  constexpr double a = 0.1, bay = 0.1;
  const int bays = std::max(1, dofs / 24 - 1);
  const double corner[4][2] = {{-a / 2, -a / 2}, {a / 2, -a / 2}, {a / 2, a / 2}, {-a / 2, a / 2}};
  json nodes = json::array(), elements = json::array();
  auto node = [](int ring, int c) { return fmt::format("n{}_{}", ring, c); };
  auto element = [&](const std::string& p, const std::string& q, const char* section) {
    elements.push_back({{"id", fmt::format("e{}", elements.size())}, {"type", "beam"}, {"nodes", {p, q}},
                        {"material", "steel"}, {"section", section}});
  };
  for (int r = 0; r <= bays; ++r)
    for (int c = 0; c < 4; ++c) nodes.push_back({{"id", node(r, c)}, {"xyz", {bay * r, corner[c][0], corner[c][1]}}});
  nodes.push_back({{"id", "A"}, {"xyz", {-bay, 0, 0}}});
  nodes.push_back({{"id", "B"}, {"xyz", {bay * (bays + 1), 0, 0}}});
  for (int r = 0; r <= bays; ++r)
    for (int c = 0; c < 4; ++c) {
      element(node(r, c), node(r, (c + 1) % 4), "tube");                  // batten
      if (r < bays) {
        element(node(r, c), node(r + 1, c), "tube");                      // chord
        element(node(r, c), node(r + 1, (c + 1) % 4), "tube");            // face diagonal
      }
    }
  for (int c = 0; c < 4; ++c) {
    element("A", node(0, c), "big");
    element(node(bays, c), "B", "big");
  }
  m["nodes"] = nodes;
  m["elements"] = elements;
  return m;
}

struct Row {
  long dofs = 0;
  double linear = 0, condense = 0, ratio = 0, ratio_min = 0, ratio_max = 0;
  int rigid_body_modes = 0;  // of the free-free link: 6 expected
};

Row measure(const json& free_link, double budget) {
  json clamped = free_link;
  clamped["supports"] = {json{{"node", "A"}, {"fix", "all"}}};
  clamped["loads"] = {json{{"node", "B"}, {"force", {0, -100.0, 50.0}}}};
  const beamfea::Model lin_model = beamfea::read_model(clamped);
  const beamfea::Model se_model = beamfea::read_model(free_link);
  const std::vector<int> interface{se_model.find_node("A"), se_model.find_node("B")};
  Row row;
  bool ok = true;
  const auto t = beamfea::bench::paired_rounds(
      {[&] {
         const auto r = beamfea::solve_linear_static(lin_model);
         row.dofs = r.free_dofs;
       },
       [&] {
         const auto r = beamfea::reduce_superelement(se_model, interface);
         if (ok && r.status != beamfea::SuperelementStatus::Succeeded)
           fmt::print(stderr, "  the condensation failed: {}\n", r.message);
         ok = ok && r.status == beamfea::SuperelementStatus::Succeeded;
         row.rigid_body_modes = static_cast<int>(r.rigid_body_modes.size());
       }},
      budget, {}, 0, 7);
  row.linear = t.median[0];
  row.condense = t.median[1];
  row.ratio = t.ratio_median[1];
  row.ratio_min = t.ratio_min[1];
  row.ratio_max = t.ratio_max[1];
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  fmt::print(stderr, "BLAS: {}\n", beamfea::bench::choose_libraries_as_the_program());
  int dofs = 10000;
  double budget = 6.0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--dofs") && i + 1 < argc) {
      dofs = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--budget") && i + 1 < argc) {
      budget = std::atof(argv[++i]);
    } else {
      fmt::print(stderr, "usage: bench_superelement_link [--dofs 10000] [--budget 6]\n");
      return 2;
    }
  }
  fmt::print("| link | free DOFs (clamped) | linear solve ms | condensation onto 2 nodes ms | condensation / linear (min-max) | rigid-body modes found |\n");
  fmt::print("|---|---|---|---|---|---|\n");
  for (const char* kind : {"beam", "lattice"}) {
    fmt::print(stderr, "{} link of about {} DOFs...\n", kind, dofs);
    const json link = std::strcmp(kind, "beam") == 0 ? beam_link(dofs) : lattice_link(dofs);
    const Row r = measure(link, budget);
    fmt::print("| {} | {} | {:.2f} | {:.2f} | **{:.2f}** ({:.2f}-{:.2f}) | {} |\n", kind, r.dofs, 1e3 * r.linear,
               1e3 * r.condense, r.ratio, r.ratio_min, r.ratio_max, r.rigid_body_modes);
  }
  return 0;
}
