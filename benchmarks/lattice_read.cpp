// bench_lattice_read: reading and checking a lattice frame model must stay linear in its size.
// For each size (lattice nodes), the cube lattice of `"generate": {"lattice": ...}` is read twice:
//   generate  the model document with the generator (io/read_generate.cpp): read_model + check_model
//   listed    the same model written out as JSON with every node and element listed (the file a
//             user without the generator ships): parse + read_model + check_model
// and the per-node CPU time printed, so that a non-linear stage shows as a growing column.
//
// Usage: bench_lattice_read [--sizes 10000,100000,350000]   (approximate node counts)
// Output: a Markdown table on stdout.
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "io/model_check.hpp"
#include "io/model_reader.hpp"

namespace {

using beamfea::bench::Stopwatch;
using json = nlohmann::json;

json generated_document(int cells) {
  json d;
  d["materials"] = json::array({{{"id", "al"}, {"E", 70e9}, {"G", 26e9}, {"density", 2700}}});
  d["sections"] = json::array({{{"id", "rod"}, {"shape", "circle"}, {"d", 0.002}}});
  d["generate"] = {{"lattice", {{"cells", {cells, cells, cells}}, {"pitch", 0.01}, {"section", "rod"}, {"material", "al"}}}};
  d["supports"] = json::array();
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) d["supports"].push_back({{"node", fmt::format("{}_{}_0", i, j)}, {"fix", "all"}});
  d["loads"] = json::array({{{"node", fmt::format("{}_{}_{}", cells, cells, cells)}, {"force", {1, 0, -1}}}});
  d["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  return d;
}

// The model of `generated` with its nodes and elements listed instead of generated.
json listed_document(const json& generated, const beamfea::Model& m) {
  json d = generated;
  d.erase("generate");
  json& nodes = d["nodes"] = json::array();
  for (const auto& n : m.nodes) nodes.push_back({{"id", n.id}, {"xyz", {n.x.x(), n.x.y(), n.x.z()}}});
  json& elements = d["elements"] = json::array();
  for (const auto& e : m.members)
    elements.push_back({{"id", e.id}, {"type", "beam"}, {"nodes", {m.nodes[e.nodes[0]].id, m.nodes[e.nodes[1]].id}},
                        {"material", "al"}, {"section", "rod"}});
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes = {10000, 100000, 350000};
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--sizes") == 0) {
      sizes.clear();
      for (const char* p = argv[i + 1]; *p;) {
        char* end = nullptr;
        sizes.push_back(std::strtol(p, &end, 10));
        p = *end ? end + 1 : end;
      }
    }
  fmt::print("| nodes | DOFs | members | JSON MB (listed) | generate: read+check s | us/node | listed: parse+read+check s | us/node |\n");
  fmt::print("|---|---|---|---|---|---|---|---|\n");
  for (const long target : sizes) {
    const int cells = std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(target)))) - 1);
    const json gen = generated_document(cells);
    Stopwatch t1;
    beamfea::Model m = beamfea::read_model(gen);
    beamfea::check_model(m, gen);
    const double t_gen = t1.cpu();
    const std::string text = listed_document(gen, m).dump();
    Stopwatch t2;
    const json parsed = json::parse(text);
    const beamfea::Model m2 = beamfea::read_model(parsed);
    beamfea::check_model(m2, parsed);
    const double t_list = t2.cpu();
    const double n = static_cast<double>(m.nodes.size());
    fmt::print("| {} | {} | {} | {:.1f} | {:.3f} | {:.2f} | {:.3f} | {:.2f} |\n", m.nodes.size(), 6 * m.nodes.size(),
               m.members.size(), static_cast<double>(text.size()) / 1e6, t_gen, 1e6 * t_gen / n, t_list, 1e6 * t_list / n);
  }
  return 0;
}
