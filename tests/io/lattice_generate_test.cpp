// "generate": {"lattice": ...} (io/read_generate.cpp): the nodes and members of a cubic lattice
// frame made by the reader, named by supports and loads, read strictly.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "solvers/linear_static.hpp"
#include "support/errors.hpp"

namespace lattice_generate_test {

using namespace beamfea;
using json = nlohmann::json;

namespace {
const double E = 70e9, G = 26e9, A = 2e-4;

json lattice_model(const json& cells, const json& pitch) {
  json d;
  d["materials"] = json::array({{{"id", "al"}, {"E", E}, {"G", G}}});
  d["sections"] = json::array({{{"id", "rod"}, {"A", A}, {"Iy", 3e-9}, {"Iz", 3e-9}, {"J", 6e-9}}});
  d["generate"] = {{"lattice", {{"cells", cells}, {"pitch", pitch}, {"section", "rod"}, {"material", "al"}}}};
  return d;
}

template <class F>
std::string error_of(F&& f) {
  const auto e = beamfea::test::thrown<InputError>(std::forward<F>(f));
  return e ? e->pointer() + " | " + e->what() : "";
}
}  // namespace

// (nx+1)(ny+1)(nz+1) nodes; nx(ny+1)(nz+1) + (nx+1)ny(nz+1) + (nx+1)(ny+1)nz edges, one element
// each; ids and positions as documented (docs/input-format.md).
TEST(LatticeGenerate, MakesTheNodesAndEdgesOfEveryCell) {
  json d = lattice_model({2, 3, 4}, {0.5, 1.0, 2.0});
  d["generate"]["lattice"]["origin"] = {1, 2, 3};
  d["generate"]["lattice"]["prefix"] = "L";
  d["nodes"] = json::array({{{"id", "extra"}, {"xyz", {-1, 0, 0}}}});
  const Model m = read_model(d);
  EXPECT_EQ(m.nodes.size(), 1u + 3 * 4 * 5);
  EXPECT_EQ(m.members.size(), 2u * 4 * 5 + 3 * 3 * 5 + 3 * 4 * 4);
  EXPECT_EQ(m.elements.size(), m.members.size());
  EXPECT_EQ(m.nodes[0].id, "extra");  // listed nodes keep their positions
  const int n = m.find_node("L2_1_3");
  ASSERT_GE(n, 0);
  EXPECT_TRUE(m.nodes[n].x.isApprox(Vec3(1 + 2 * 0.5, 2 + 1 * 1.0, 3 + 3 * 2.0)));
  const int e = m.find_member("Lz2_1_2");
  ASSERT_GE(e, 0);
  EXPECT_EQ(m.members[e].nodes[0], m.find_node("L2_1_2"));
  EXPECT_EQ(m.members[e].nodes[1], n);
  EXPECT_LT(m.find_member("Lx2_1_2"), 0);  // no x edge leaves the last plane
}

// A lattice column: 1 x 1 x n cells, the four bottom nodes fixed, P down on each top node. By
// symmetry every vertical member carries P and the rungs carry nothing: the top moves down by
// delta = P n p / (E A) exactly (a bar in tension-compression).
TEST(LatticeGenerate, LatticeColumnShortensAsFourBars) {
  const int n = 6;
  const double p = 0.25, P = 1e3;
  json d = lattice_model({1, 1, n}, p);
  d["supports"] = json::array();
  d["loads"] = json::array();
  for (const char* c : {"0_0", "1_0", "0_1", "1_1"}) {
    d["supports"].push_back({{"node", std::string(c) + "_0"}, {"fix", {"ux", "uy", "uz", "rx", "ry", "rz"}}});
    d["loads"].push_back({{"node", std::string(c) + "_" + std::to_string(n)}, {"force", {0, 0, -P}}});
  }
  const Model m = read_model(d);
  const LinearStaticResult r = LinearSystem(m).solve(m.default_loads());
  ASSERT_EQ(r.status, SolveStatus::Succeeded) << r.message;
  const double delta = P * n * p / (E * A);
  for (const char* c : {"0_0", "1_0", "0_1", "1_1"}) {
    const int node = m.find_node(std::string(c) + "_" + std::to_string(n));
    EXPECT_NEAR(r.u[6 * node + 2], -delta, 1e-9 * delta) << c;
    EXPECT_NEAR(r.u[6 * node + 0], 0.0, 1e-9 * delta) << c;
  }
}

TEST(LatticeGenerate, RefusesUnknownKeysAndSizesBeyondTheLimit) {
  json d = lattice_model({2, 2, 2}, 1.0);
  d["generate"]["lattice"]["cell"] = 1;
  EXPECT_NE(error_of([&] { read_model(d); }).find("/generate/lattice/cell"), std::string::npos);
  EXPECT_NE(error_of([&] { read_model(lattice_model({100, 100, 100}, 1.0)); }).find("exceed the limit of 1000000"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_model(lattice_model({2, 0, 2}, 1.0)); }).find("/generate/lattice/cells/1"), std::string::npos);
  EXPECT_NE(error_of([&] { read_model(lattice_model({2, 2, 2}, json::array({1, -1, 1}))); }).find("/generate/lattice/pitch/1"),
            std::string::npos);
  json taken = lattice_model({1, 1, 1}, 1.0);
  taken["nodes"] = json::array({{{"id", "0_0_0"}, {"xyz", {5, 5, 5}}}});
  EXPECT_NE(error_of([&] { read_model(taken); }).find("node id '0_0_0' is taken"), std::string::npos);
  json bad_section = lattice_model({1, 1, 1}, 1.0);
  bad_section["generate"]["lattice"]["section"] = "tube";
  EXPECT_EQ(error_of([&] { read_model(bad_section); }).substr(0, 26), "/generate/lattice/section ");
}

}  // namespace lattice_generate_test
