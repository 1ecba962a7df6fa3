// Loads, masses, gravity, load cases and combinations in the model file: bad input names its JSON
// pointer (exit code 2 from the CLI); results carry stations, fixed-end forces and one
// factorisation for all linear cases.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/run.hpp"
#include "support/errors.hpp"
#include "support/models.hpp"

namespace loads_input_test {

using namespace beamfea;
using nlohmann::json;

namespace {
json base() {
  json doc = test::cantilever(2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6, 4);
  doc["materials"][0]["density"] = 7850.0;
  return doc;
}

std::string error_pointer(const json& doc) { return test::input_error_pointer(doc); }
}  // namespace

TEST(LoadsInput, BadInputNamesTheField) {
  {
    json d = base();
    d["loads"].push_back({{"element", "nope"}, {"distributed", {0, 0, -1}}});
    EXPECT_EQ(error_pointer(d), "/loads/0/element");
  }
  {
    json d = base();
    d["loads"].push_back({{"element", "e"}, {"distributed", {0, 0, -1}}, {"from", 1.2}});
    EXPECT_EQ(error_pointer(d), "/loads/0/from");
  }
  {
    json d = base();
    d["loads"].push_back({{"element", "e"}, {"distributed", {0, 0, -1}}, {"from", 0.7}, {"to", 0.2}});
    EXPECT_EQ(error_pointer(d), "/loads/0/to");
  }
  {
    json d = base();
    d["loads"].push_back({{"element", "e"}, {"point", {0, 0, -1}}, {"at", -0.1}});
    EXPECT_EQ(error_pointer(d), "/loads/0/at");
  }
  {
    json d = base();
    d["materials"][0]["density"] = -1.0;
    EXPECT_EQ(error_pointer(d), "/materials/0/density");
  }
  {
    json d = base();
    d["masses"] = json::array({{{"node", "Z"}, {"mass", 1.0}}});
    EXPECT_EQ(error_pointer(d), "/masses/0/node");
  }
  {
    json d = base();
    d["masses"] = json::array({{{"node", "B"}, {"mass", 1.0}, {"inertia", {{1, 2, 0}, {2, 1, 0}, {0, 0, 1}}}}});
    EXPECT_EQ(error_pointer(d), "/masses/0/inertia");  // indefinite
  }
  {
    json d = base();
    d["load_cases"] = json::array({{{"id", "dead"}, {"gravity", {0, 0, -9.81}}}});
    d["combinations"] = json::array({{{"id", "c"}, {"factors", {{"dead", 1.0}, {"live", 1.5}}}}});
    EXPECT_EQ(error_pointer(d), "/combinations/0/factors/live");
  }
  {
    json d = base();
    d["load_cases"] = json::array({{{"id", "dead"}}, {{"id", "dead"}}});
    EXPECT_EQ(error_pointer(d), "/load_cases/1/id");
  }
  {
    json d = base();
    d["analyses"] = json::array({{{"id", "a"}, {"type", "linear_static"}, {"load_case", "nope"}}});
    EXPECT_EQ(error_pointer(d), "/analyses/0/load_case");
  }
  {
    json d = base();
    d["loads"].push_back({{"element", "e"}, {"distributed", {0, 0, -1}}, {"form", 0.1}});
    EXPECT_EQ(error_pointer(d), "/loads/0/form");
  }
}

TEST(LoadsInput, CliExitsWithTwoOnAMassOnAnUnknownNode) {
  const auto dir = test::temp_dir("loads_bad_mass");
  json d = base();
  d["masses"] = json::array({{{"node", "nowhere"}, {"mass", 2.0}}});
  test::write_file(dir / "m.json", d.dump());
  const auto r = test::run_cli("check " + (dir / "m.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/masses/0/node"), std::string::npos) << r.output;
}

TEST(LoadsInput, ResultsCarryStationsFixedEndForcesAndOneFactorisation) {
  // Cantilever, uniform q down on its 4 segments: root moment q L^2 / 2 from end_forces (which
  // include the fixed-end forces), stations at the ends, segment ends and 10 interior points.
  const double q = 1000.0, L = 2.0;
  json d = base();
  d["materials"][0]["density"] = 0.0;
  d["load_cases"] = json::array({{{"id", "q"}, {"loads", json::array({{{"element", "e"}, {"distributed", {0, 0, -q}}}})}},
                                 {{"id", "q2"}, {"loads", json::array({{{"element", "e"}, {"distributed", {0, 0, -2 * q}}}})}}});
  d["analyses"] = json::array({{{"id", "a"}, {"type", "linear_static"}, {"load_case", "q"}},
                               {{"id", "b"}, {"type", "linear_static"}, {"load_case", "q2"}, {"stations", 3}}});
  const Model m = load_and_check(d);
  const auto dir = test::temp_dir("loads_results");
  RunOptions o;
  o.out_dir = dir;
  const auto rep = run_document(m, d, o);
  ASSERT_FALSE(rep.failed);
  EXPECT_EQ(rep.results["factorizations"], 1);
  const auto& a = rep.results["analyses"]["a"];
  EXPECT_EQ(a["factorizations"], 1);
  EXPECT_EQ(rep.results["analyses"]["b"]["factorizations"], 1);
  const auto& st = a["elements"]["e"]["stations"];
  ASSERT_EQ(st.size(), 2u + 3u + 10u);  // ends, 3 segment joints, 10 interior at L k / 11
  for (const auto& s : st) {
    const double x = s["x"].get<double>();
    EXPECT_NEAR(s["forces"][4].get<double>(), q * (L - x) * (L - x) / 2, 1e-9 * q * L * L) << x;  // My (hogging)
    EXPECT_NEAR(s["forces"][2].get<double>(), -q * (L - x), 1e-9 * q * L) << x;
  }
  const auto& ef = a["elements"]["e"]["end_forces"];
  EXPECT_NEAR(ef[0][4].get<double>(), -q * L * L / 2, 1e-9 * q * L * L);
  // 3 interior stations at L k / 4 fall on the segment joints: one station each.
  EXPECT_EQ(rep.results["analyses"]["b"]["elements"]["e"]["stations"].size(), 5u);
  // The .vtu carries the diagrams.
  std::ifstream f(dir / "a.vtu");
  const std::string vtu((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(vtu.find("\"diagram_My\""), std::string::npos);
  EXPECT_NE(vtu.find("\"section_forces\""), std::string::npos);
}

}  // namespace loads_input_test
