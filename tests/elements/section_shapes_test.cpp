// Section shapes (elements/section_shapes.hpp) against an independent computation: the section
// integrated cell by cell over a grid (midpoint rule on cells whose edges fall on the plates'
// edges, each cell's own b h^3/12 added: exact for plate assemblies), Saint-Venant's and Bredt's
// torsion constants written out, and a rolled section's published properties.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

#include "elements/section_shapes.hpp"

namespace section_shapes_test {

using namespace beamfea;

namespace {

// A, Iy = int (z - zc)^2, Iz = int (y - yc)^2, Iyz of the region inside(y, z) within the box
// [y0, y1] x [z0, z1], on square cells of side `cell` (an exact result when every edge of the
// region lies on a cell edge).
SectionProperties integrate(const std::function<bool(double, double)>& inside, double y0, double y1, double z0, double z1,
                            double cell) {
  const int ny = static_cast<int>(std::lround((y1 - y0) / cell)), nz = static_cast<int>(std::lround((z1 - z0) / cell));
  double A = 0, Sy = 0, Sz = 0, Iyy = 0, Izz = 0, Iyz = 0;
  const double a = cell * cell, own = a * cell * cell / 12.0;
  for (int i = 0; i < ny; ++i)
    for (int k = 0; k < nz; ++k) {
      const double y = y0 + (i + 0.5) * cell, z = z0 + (k + 0.5) * cell;
      if (!inside(y, z)) continue;
      A += a, Sy += a * z, Sz += a * y;
      Iyy += a * z * z + own, Izz += a * y * y + own, Iyz += a * y * z;
    }
  SectionProperties s;
  const double yc = Sz / A, zc = Sy / A;
  s.A = A, s.Iy = Iyy - A * zc * zc, s.Iz = Izz - A * yc * yc, s.Iyz = Iyz - A * yc * zc;
  return s;
}

void expect_same_plates(const SectionProperties& got, const SectionProperties& grid) {
  const double tol = 1e-9;  // rounding only: the grid integration is exact on these dimensions
  EXPECT_NEAR(got.A, grid.A, tol * grid.A);
  EXPECT_NEAR(got.Iy, grid.Iy, tol * grid.Iy);
  EXPECT_NEAR(got.Iz, grid.Iz, tol * grid.Iz);
  EXPECT_NEAR(got.Iyz, grid.Iyz, tol * std::max(grid.Iy, grid.Iz));
}

bool in(double v, double lo, double hi) { return v > lo && v < hi; }

}  // namespace

// Dimensions in mm, multiples of the 0.5 mm cell.
TEST(SectionShapes, IShapeEqualsItsPlatesIntegrated) {
  const double h = 300, b = 150, tw = 7, tf = 11;
  const auto grid = integrate([&](double y, double z) { return std::abs(z) > h / 2 - tf ? true : std::abs(y) < tw / 2; }, -b / 2,
                              b / 2, -h / 2, h / 2, 0.5);
  const SectionProperties s = i_section(h, b, tw, tf);
  expect_same_plates(s, grid);
  // Saint-Venant's open thin-walled section: J = sum l t^3 / 3 (Timoshenko & Goodier, Theory of
  // Elasticity, 3rd ed., sec. 112) over two flanges b x tf and the web (h - 2 tf) x tw.
  EXPECT_NEAR(s.J, (2 * b * std::pow(tf, 3) + (h - 2 * tf) * std::pow(tw, 3)) / 3, 1e-9 * s.J);
  // Eurocode 3's web shear area with r = 0: A - 2 b tf + tw tf.
  EXPECT_NEAR(s.kz, s.A / ((h - tf) * tw), 1e-12 * s.kz);
}

TEST(SectionShapes, ChannelTeeAndAngleEqualTheirPlatesIntegrated) {
  const double h = 200, b = 80, tw = 6, tf = 11;
  expect_same_plates(channel_section(h, b, tw, tf),
                     integrate([&](double y, double z) { return y < tw || std::abs(z) > h / 2 - tf; }, 0, b, -h / 2, h / 2, 0.5));
  expect_same_plates(tee_section(h, b, tw, tf),
                     integrate([&](double y, double z) { return z > h - tf || std::abs(y) < tw / 2; }, -b / 2, b / 2, 0, h, 0.5));
  const double ha = 120, ba = 80, t = 10;  // an unequal angle: heel at y = z = 0
  const auto angle = angle_section(ha, ba, t);
  expect_same_plates(angle, integrate([&](double y, double z) { return y < t || z < t; }, 0, ba, 0, ha, 0.5));
  EXPECT_LT(angle.Iyz, 0.0);  // the legs' material lies where (y - yc)(z - zc) < 0
  EXPECT_NEAR(angle.J, (ha + ba - t) * t * t * t / 3, 1e-9 * angle.J);
}

TEST(SectionShapes, BoxEqualsItsWallsIntegratedAndBredtsTorsionConstant) {
  const double h = 200, b = 100, t = 8;
  const auto s = box_section(h, b, t);
  expect_same_plates(s, integrate([&](double y, double z) { return !(in(y, t, b - t) && in(z, t, h - t)); }, 0, b, 0, h, 0.5));
  // Bredt (thin-walled closed section): J = 4 A_m^2 t / s, A_m = (b - t)(h - t), s = 2 (b - t + h - t).
  const double Am = (b - t) * (h - t);
  EXPECT_NEAR(s.J, 4 * Am * Am * t / (2 * (b - t + h - t)), 1e-9 * s.J);
  EXPECT_NEAR(s.kz, (b + h) / h, 1e-12);
}

// The fillets: four spandrels (square r x r less a quarter disc) at the web-flange junctions,
// integrated on a fine grid (the arcs are not on cell edges: the midpoint rule's error is about
// the cells cut by the arc, below 1e-4 of A and I at this cell size).
TEST(SectionShapes, RootRadiiAddTheSpandrelsBetweenWebAndFlanges) {
  const double h = 300, b = 150, tw = 7, tf = 11, r = 15;
  const auto inside = [&](double y, double z) {
    const double ay = std::abs(y), az = std::abs(z);
    if (az > h / 2 - tf || ay < tw / 2) return true;
    const double cy = tw / 2 + r, cz = h / 2 - tf - r;  // the arc's centre
    return ay < cy && az > cz && std::hypot(ay - cy, az - cz) > r;
  };
  const auto grid = integrate(inside, -b / 2, b / 2, -h / 2, h / 2, 0.05);
  const auto s = i_section(h, b, tw, tf, r);
  EXPECT_NEAR(s.A, grid.A, 1e-4 * grid.A);
  EXPECT_NEAR(s.Iy, grid.Iy, 1e-4 * grid.Iy);
  EXPECT_NEAR(s.Iz, grid.Iz, 1e-4 * grid.Iz);
  EXPECT_NEAR(s.A - i_section(h, b, tw, tf).A, (4 - std::numbers::pi) * r * r, 1e-9 * r * r);
}

// Published properties of rolled sections (ArcelorMittal, "Sales programme: sections and merchant
// bars", IPE 300 and HEA 200; cm^2 and cm^4 converted to mm): the plates alone fall short by the
// fillets' share (3-4 % of A and Iy, about 30 % of J), the root radius r closes it.
struct Rolled {
  const char* name;
  double h, b, tw, tf, r;   // mm
  double A, Iy, Iz, J;      // published, mm^2 and mm^4
};
TEST(SectionShapes, RolledSectionsMatchPublishedTablesWithTheirRootRadii) {
  for (const Rolled& p : {Rolled{"IPE 300", 300, 150, 7.1, 10.7, 15, 53.81e2, 8356e4, 603.8e4, 20.12e4},
                          Rolled{"HEA 200", 190, 200, 6.5, 10, 18, 53.83e2, 3692e4, 1336e4, 20.98e4}}) {
    SCOPED_TRACE(p.name);
    const auto plates = i_section(p.h, p.b, p.tw, p.tf);
    EXPECT_NEAR(plates.A, p.A, 0.06 * p.A);
    EXPECT_NEAR(plates.Iy, p.Iy, 0.05 * p.Iy);
    EXPECT_NEAR(plates.Iz, p.Iz, 0.05 * p.Iz);
    EXPECT_LT(plates.J, 0.85 * p.J);  // the fillets carry about 30 % of J
    const auto rolled = i_section(p.h, p.b, p.tw, p.tf, p.r);
    EXPECT_NEAR(rolled.A, p.A, 0.002 * p.A);
    EXPECT_NEAR(rolled.Iy, p.Iy, 0.002 * p.Iy);
    EXPECT_NEAR(rolled.Iz, p.Iz, 0.003 * p.Iz);
    EXPECT_NEAR(rolled.J, p.J, 0.03 * p.J);  // El Darwish and Johnston's fit
  }
}

TEST(SectionShapes, AnEqualAngleHasItsPrincipalAxesAtFortyFiveDegrees) {
  const auto s = angle_section(100, 100, 10);
  const auto pm = principal_moments(s.Iy, s.Iz, s.Iyz);
  EXPECT_NEAR(pm.I1, s.Iy + std::abs(s.Iyz), 1e-9 * s.Iy);
  EXPECT_NEAR(pm.I2, s.Iy - std::abs(s.Iyz), 1e-9 * s.Iy);
  EXPECT_NEAR(std::abs(pm.angle), std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(pm.I1 + pm.I2, s.Iy + s.Iz, 1e-9 * s.Iy);  // the trace is invariant
}

TEST(SectionShapes, NamedDimensionsAreCheckedAndNamedWhenWrong) {
  EXPECT_NEAR(section_properties("box", {{"h", 2}, {"b", 1}, {"t", 0.1}}).A, box_section(2, 1, 0.1).A, 1e-15);
  const auto message = [](std::string_view shape, const std::vector<std::pair<std::string, double>>& d) {
    try {
      section_properties(shape, d);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("hexagon", {}).find("unknown shape 'hexagon'"), std::string::npos);
  EXPECT_NE(message("i", {{"h", 1}, {"b", 1}, {"tw", 0.1}}).find("needs tf"), std::string::npos);
  EXPECT_NE(message("i", {{"h", 1}, {"b", 1}, {"tw", 0.1}, {"tf", 0.6}}).find("tf:"), std::string::npos);
  EXPECT_NE(message("box", {{"h", 1}, {"b", 1}, {"t", 0.1}, {"tw", 0.1}}).find("not 'tw'"), std::string::npos);
  EXPECT_NE(message("angle", {{"h", 1}, {"b", -1}, {"t", 0.1}}).find("b: must be a positive"), std::string::npos);
  EXPECT_NE(message("circle", {{"d", 1}, {"r", 0.5}}).find("one of them"), std::string::npos);
}

}  // namespace section_shapes_test
