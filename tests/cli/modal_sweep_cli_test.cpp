// Modal results in `beamfea sweep` outputs: the first two frequencies of a
// point mass on a massless cantilever over a grid of lengths and masses, from the program's table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "support/sweep_util.hpp"

namespace modal_sweep_cli_test {

using namespace sweep_test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, Iz = 1e-6, Iy = 2e-6;

// The sweep cantilever (E = 210e9, Iz = 1e-6, Iy = 2e-6) with no density, a point mass at its tip
// and a modal analysis of two modes.
json massive_tip_cantilever() {
  json d = cantilever(1.0, 0.0);
  d["masses"] = {{{"node", "B"}, {"mass", 1.0}}};
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 2}}};
  d.erase("loads");
  return d;
}
}  // namespace

// Grid L x m (3 x 2). A point mass m on a massless cantilever (one Hermite element: exact in
// statics) vibrates at f = sqrt(3 E I / (m L^3)) / (2 pi) in each bending plane (Blevins, Formulas
// for Natural Frequency and Mode Shape, 1979, Table 6-2, case 1 with a massless beam): Iz (bending
// in y) gives the first, Iy the second. Asserted to 1e-9 in every row of cases.csv.
TEST(ModalSweep, FirstFrequencyOverAGridOfLengthsAndMassesIsTheClosedForm) {
  const auto dir = temp_dir("modal_sweep");
  const json sweep = {{"grid", {json{{"name", "L"}, {"pointer", "/nodes/1/xyz/0"}, {"values", {0.5, 1.0, 2.0}}},
                                json{{"name", "m"}, {"pointer", "/masses/0/mass"}, {"values", {1.0, 10.0}}}}},
                      {"outputs", {json{{"name", "f1"}, {"path", "analyses.m.frequencies[0]"}},
                                   json{{"name", "f2"}, {"path", "analyses.m.frequencies[1]"}}}}};
  const auto file = write_sweep(dir, sweep, massive_tip_cantilever());
  const std::string cmd = std::string(BEAMFEA_EXE) + " sweep " + file.string() + " --out " + (dir / "out").string() +
                          " -q --progress none";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  bool well_formed = false;
  const Csv t = read_csv(dir / "out" / "cases.csv", &well_formed);
  ASSERT_TRUE(well_formed);
  ASSERT_EQ(t.rows.size(), 6u);
  const int cL = t.col("L"), cm = t.col("m"), c1 = t.col("f1"), c2 = t.col("f2"), st = t.col("status");
  ASSERT_GE(cL, 0);
  ASSERT_GE(cm, 0);
  ASSERT_GE(c1, 0);
  ASSERT_GE(c2, 0);
  for (const auto& r : t.rows) {
    EXPECT_EQ(r[st], "ok");
    const double L = std::stod(r[cL]), m = std::stod(r[cm]);
    const double f1 = std::sqrt(3 * E * Iz / (m * L * L * L)) / (2 * pi);
    const double f2 = std::sqrt(3 * E * Iy / (m * L * L * L)) / (2 * pi);
    EXPECT_NEAR(std::stod(r[c1]), f1, 1e-9 * f1) << "L " << L << ", m " << m;
    EXPECT_NEAR(std::stod(r[c2]), f2, 1e-9 * f2) << "L " << L << ", m " << m;
  }
}

}  // namespace modal_sweep_cli_test
