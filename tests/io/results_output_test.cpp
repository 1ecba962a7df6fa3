// results.json keys (a contract) and the VTK file.
#include <gtest/gtest.h>

#include <sstream>

#include "io/vtk_writer.hpp"
#include "support/models.hpp"

namespace results_output_test {

using namespace beamfea;
using nlohmann::json;

TEST(ResultsOutput, ContainsTheContractKeysAndAVtuFile) {
  json d = test::cantilever(2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6, 4);
  d["nodes"].push_back({{"id", "D"}, {"xyz", {2, 0, 0}}});
  d["joints"] = {{{"id", "j1"}, {"type", "revolute"}, {"nodes", {"B", "D"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {1e4}}}};
  d["loads"] = {{{"node", "D"}, {"force", {0, -1000, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}, {{"id", "K"}, {"type", "stiffness"}, {"node", "D"}}};
  const auto dir = test::temp_dir("results");
  test::write_file(dir / "model.json", d.dump());
  const auto r = test::run_cli("run " + (dir / "model.json").string() + " --out " + (dir / "out").string() + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json res = test::read_json(dir / "out" / "results.json");
  const auto& lin = res["analyses"]["lin"];
  ASSERT_TRUE(lin["nodes"]["D"]["displacement"].is_array());
  EXPECT_EQ(lin["nodes"]["D"]["displacement"].size(), 6u);
  EXPECT_EQ(lin["nodes"]["A"]["reaction"].size(), 6u);
  EXPECT_FALSE(lin["nodes"]["D"].contains("reaction"));
  EXPECT_EQ(lin["elements"]["e"]["end_forces"].size(), 2u);
  EXPECT_EQ(lin["elements"]["e"]["segments"].size(), 4u);
  EXPECT_EQ(lin["joints"]["j1"]["coordinates"].size(), 1u);
  // Hinge rotation of the spring: M / k with M = P * 0 (the load acts at the joint) -> 0, and the
  // reaction carries the load across.
  EXPECT_NEAR(lin["joints"]["j1"]["reaction"][1].get<double>(), 1000.0, 1e-6);
  // Reaction balances the load.
  EXPECT_NEAR(lin["nodes"]["A"]["reaction"][1].get<double>(), 1000.0, 1e-6);
  const auto& K = res["analyses"]["K"];
  EXPECT_EQ(K["matrix"].size(), 6u);
  EXPECT_EQ(K["matrix"][0].size(), 6u);
  EXPECT_EQ(K["rank"].get<int>(), 6);
  // VTK: a .vtu with the documented arrays.
  ASSERT_TRUE(std::filesystem::exists(dir / "out" / "lin.vtu"));
  const std::string vtu = test::read_text(dir / "out" / "lin.vtu");
  for (const char* name : {"UnstructuredGrid", "\"displacement\"", "\"rotation\"", "\"section_forces\"", "\"id\""})
    EXPECT_NE(vtu.find(name), std::string::npos) << name;
  // No temporary files are left behind.
  for (const auto& e : std::filesystem::directory_iterator(dir / "out"))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

// The .vtu is read back by VTK's own XML reader (the one ParaView uses), through Debian's
// python3-vtk9: points, cells, arrays and the maximum displacement must match results.json.
TEST(ResultsOutput, VtuOpensInVtksOwnReader) {
  json d = test::linear_cantilever(-1000.0, 2);
  const auto dir = test::temp_dir("vtkread");
  test::write_file(dir / "model.json", d.dump());
  auto r = test::run_cli("run " + (dir / "model.json").string() + " --out " + (dir / "out").string() + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  test::write_file(dir / "read.py",
                   "import sys, vtk\n"
                   "r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update()\n"
                   "g = r.GetOutput(); d = g.GetPointData().GetArray('displacement')\n"
                   "print(g.GetNumberOfCells(), min(d.GetComponent(i, 1) for i in range(g.GetNumberOfPoints())),\n"
                   "      g.GetCellData().GetArray('section_forces').GetNumberOfComponents())\n");
  const std::string cmd = "/usr/bin/python3 " + (dir / "read.py").string() + " " + (dir / "out" / "lin.vtu").string() + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[512] = {0};
  std::string out;
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  ASSERT_EQ(pclose(p), 0) << out;
  std::istringstream in(out);
  int cells = 0, components = 0;
  double min_uy = 0.0;
  in >> cells >> min_uy >> components;
  EXPECT_EQ(cells, 2 * 8);  // two elements, 8 line cells each
  EXPECT_NEAR(min_uy, -1000.0 * 8.0 / (3 * 2.1e11 * 3e-6), 1e-12);  // tip: P L^3 / 3EI
  EXPECT_EQ(components, 6);
}

// A large model's beams are drawn in fewer segments, so that the .vtu's beams stay within
// kVtkBeamCellBudget (1,000,000) line cells: 8 up to 125,000 beams, then 1,000,000 / beams, at
// least 1. Rigid links (one cell each) do not count.
TEST(ResultsOutput, LargeModelsDrawTheirBeamsInFewerSegments) {
  Model m;
  auto with = [&m](std::size_t beams, std::size_t rigid) {
    m.elements.assign(beams, Element{});
    for (auto& el : m.elements) el.type = MemberType::Beam;
    Element link;
    link.type = MemberType::Rigid;
    m.elements.insert(m.elements.end(), rigid, link);
    return vtk_beam_segments(m);
  };
  EXPECT_EQ(with(1, 0), 8);
  EXPECT_EQ(with(125'000, 0), 8);
  EXPECT_EQ(with(125'001, 0), 7);
  EXPECT_EQ(with(201'720, 0), 4);  // the 40^3-cell lattice of benchmarks/lattice_model.py
  EXPECT_EQ(with(1'014'300, 0), 1);  // its 69^3-cell one (2,028,600 free DOFs)
  EXPECT_EQ(with(0, 10), 8);
  EXPECT_EQ(with(100'000, 900'000), 8);
}

}  // namespace results_output_test
