// Frequencies along a path through the model file and the CLI (analysis "path", key
// "frequencies"): the numbers in results.json and the CSV against the closed form, and bad input
// exiting 2 naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace path_frequencies_cli_test {

using namespace beamfea;
using nlohmann::json;

namespace {

constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 80e9, rho = 7850.0, L = 3.0, A = 1e-3, I = 1e-9;
const int kElements = 16;

// A pinned column (weak plane x-z) loaded by its Euler load P_cr at B, along x.
json column() {
  json d = test::cantilever(L, E, G, A, I, 4 * I, 2 * I, kElements);
  d["materials"][0]["density"] = rho;
  d["supports"] = {{{"node", "A"}, {"fix", {"ux", "uy", "uz", "rx"}}}, {{"node", "B"}, {"fix", {"uy", "uz"}}}};
  d["loads"] = {{{"node", "B"}, {"force", {-pi * pi * E * I / (L * L), 0, 0}}}};
  return d;
}

void expect_bad(const json& d, const std::string& name, const std::vector<std::string>& fragments) {
  test::expect_bad_input(test::run_model(name, d), fragments);
}

}  // namespace

// Load control to 0.8 P_cr with "frequencies": {"modes": 2, "mass": "consistent"}: at every step
// f_1/f_1(0) = sqrt(1 - lambda P_cr/P_cr,n), P_cr,n = P_cr / c_n the co-rotational column's discrete
// Euler load (c_n = (2 n^2/pi^2)(1 - cos(pi/n)), see tests/solvers/path_frequencies_test.cpp),
// to 2e-4; f_1(0) = pi^2 sqrt(EI/(rho A L^4))/(2 pi) to 1e-5; the CSV carries the same numbers.
TEST(PathFrequenciesCli, ColumnFrequenciesInResultsAndCsvFollowTheClosedForm) {
  json d = column();
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 0.8}, {"increments", 4}}},
                    {"frequencies", {{"modes", 2}, {"mass", "consistent"}}}}};
  const test::CliCase r = test::run_model("path_freq_ok", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const json res = r.results();
  const json& steps = res["analyses"]["p"]["steps"];
  ASSERT_GE(steps.size(), 3u);
  const double f0 = pi * pi * std::sqrt(E * I / (rho * A * std::pow(L, 4))) / (2 * pi);
  const double cn = 2.0 * kElements * kElements / (pi * pi) * (1.0 - std::cos(pi / kElements));
  const double f_start = steps[0]["frequencies"][0].get<double>();
  EXPECT_NEAR(f_start, f0, 1e-5 * f0);
  for (const auto& s : steps) {
    // All corrector iterations, of which the chord's (docs/analyses/path.md).
    ASSERT_TRUE(s.contains("chord_iterations")) << s.dump();
    EXPECT_GE(s["iterations"].get<long>(), s["chord_iterations"].get<long>());
    EXPECT_GE(s["chord_iterations"].get<long>(), 0);
    ASSERT_EQ(s["frequencies"].size(), 2u);
    const double lam = s["load_factor"].get<double>();
    EXPECT_NEAR(s["frequencies"][0].get<double>() / f_start, std::sqrt(1.0 - lam * cn), 2e-4) << "lambda " << lam;
  }
  EXPECT_NEAR(steps.back()["load_factor"].get<double>(), 0.8, 1e-12);
  // The CSV: columns f1, f2 at the end of each row.
  std::ifstream csv(r.out() / "p.csv");
  std::string header, row, last;
  std::getline(csv, header);
  EXPECT_NE(header.find(",f1,f2"), std::string::npos) << header;
  while (std::getline(csv, row))
    if (!row.empty()) last = row;
  const auto comma = last.rfind(',');
  const auto comma1 = last.rfind(',', comma - 1);
  EXPECT_NEAR(std::stod(last.substr(comma1 + 1, comma - comma1 - 1)),
              steps.back()["frequencies"][0].get<double>(), 1e-12 * f0);
}

// Bad "frequencies": unknown key (nearest suggested), bad mass, too many modes, a model without
// mass: exit 2 naming the pointer, no results written.
TEST(PathFrequenciesCli, BadFrequencySpecsExitTwoNamingTheField) {
  json d = column();
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 0.5}}},
                    {"frequencies", {{"mode", 2}}}}};
  expect_bad(d, "path_freq_key", {"/analyses/0/frequencies", "mode", "modes"});
  d["analyses"][0]["frequencies"] = {{"modes", 2}, {"mass", "heavy"}};
  expect_bad(d, "path_freq_mass", {"/analyses/0/frequencies/mass", "heavy"});
  d["analyses"][0]["frequencies"] = {{"modes", 0}};
  expect_bad(d, "path_freq_zero", {"/analyses/0/frequencies/modes"});
  d["analyses"][0]["frequencies"] = {{"modes", 10000}};
  expect_bad(d, "path_freq_many", {"/analyses/0/frequencies/modes"});
  d["analyses"][0]["frequencies"] = {{"modes", 200}};  // 16 elements: 17 nodes, 96 - ... free DOFs < 200
  expect_bad(d, "path_freq_dofs", {"/analyses/0/frequencies/modes", "free DOFs"});
  d["analyses"][0]["frequencies"] = 3;
  expect_bad(d, "path_freq_type", {"/analyses/0/frequencies"});
  json nomass = column();
  nomass["materials"][0].erase("density");
  nomass["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 0.5}}},
                         {"frequencies", {{"modes", 1}}}}};
  expect_bad(nomass, "path_freq_nomass", {"/analyses/0/frequencies", "no mass"});
}

}  // namespace path_frequencies_cli_test
