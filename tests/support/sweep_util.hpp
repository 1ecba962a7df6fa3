#pragma once
// Shared by the sweep tests: a cantilever base model, temporary folders and table reading.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/sweep_table.hpp"
#include "support/files.hpp"

namespace sweep_test {

using json = nlohmann::json;
namespace fs = std::filesystem;

// A cantilever along x: node A clamped, tip node B at x = L, tip force (0, P, 0).
// Euler-Bernoulli closed forms (Gere & Goodno, Mechanics of Materials, Table G-1 case 4;
// Przemieniecki, Theory of Matrix Structural Analysis, eq. 5.116):
//   tip deflection  v = P L^3 / (3 E Iz);
//   stiffness of the tip node with all six DOFs kept = the element's k_BB block, whose
//   entries are K[uy][uy] = 12 E Iz / L^3, K[uy][rz] = -6 E Iz / L^2, K[rz][rz] = 4 E Iz / L.
constexpr double kE = 210e9, kIz = 1e-6, kIy = 2e-6;

inline json cantilever(double L = 2.0, double P = -1000.0) {
  return json::parse(R"({
    "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [2, 0, 0]}],
    "materials": [{"id": "steel", "E": 210e9, "nu": 0.3}],
    "sections": [{"id": "s", "A": 1e-3, "Iy": 2e-6, "Iz": 1e-6, "J": 3e-6}],
    "elements": [{"id": "e1", "type": "beam", "nodes": ["A", "B"], "material": "steel", "section": "s"}],
    "supports": [{"node": "A", "fix": "all"}],
    "loads": [{"node": "B", "force": [0, -1000, 0]}],
    "analyses": [{"id": "lin", "type": "linear_static"}, {"id": "K", "type": "stiffness", "node": "B"}]
  })")
      .patch(json::array({json{{"op", "replace"}, {"path", "/nodes/1/xyz/0"}, {"value", L}},
                          json{{"op", "replace"}, {"path", "/loads/0/force/1"}, {"value", P}}}));
}

// A fresh folder under the system's temporary folder.
inline fs::path temp_dir(const std::string& name) {
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  fs::path d = fs::temp_directory_path() / ("beamfea_" + name + "_" + std::to_string(stamp));
  fs::create_directories(d);
  return d;
}

inline void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

inline std::string read(const fs::path& p) { return beamfea::test::read_text(p); }

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
  // The table without its wall-time column (the only one that may differ between runs).
  std::vector<std::vector<std::string>> without_time() const {
    auto r = rows;
    const int t = col("wall_time_s");
    for (auto& row : r) row.erase(row.begin() + t);
    return r;
  }
};

// Reads a table; every line must be complete and have the header's number of fields.
inline Csv read_csv(const fs::path& p, bool* well_formed = nullptr) {
  Csv c;
  const std::string text = read(p);
  bool ok = !text.empty() && text.back() == '\n';
  std::istringstream in(text);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    auto f = beamfea::csv_split(line);
    if (first) {
      c.header = f;
      first = false;
    } else {
      ok = ok && f.size() == c.header.size();
      c.rows.push_back(f);
    }
  }
  if (well_formed) *well_formed = ok;
  return c;
}

// Writes base.json and sweep.json into `dir`; returns the sweep file's path.
inline fs::path write_sweep(const fs::path& dir, const json& sweep, const json& base = cantilever()) {
  write(dir / "base.json", base.dump(2));
  json s = sweep;
  if (!s.contains("model")) s["base"] = "base.json";
  write(dir / "sweep.json", s.dump(2));
  return dir / "sweep.json";
}

}  // namespace sweep_test
