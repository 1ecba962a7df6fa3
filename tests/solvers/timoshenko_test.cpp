// Timoshenko beams through the analyses other than modal: stiffness, buckling, path following.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "nl_models.hpp"
#include "solvers/buckling.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/path_following.hpp"

namespace timoshenko_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 80e9;
// A stubby rectangular member (L/h = 5): shear flexibility is ~10 % of bending's.
const double L = 1.0, b = 0.1, h = 0.2, A = b * h, Iy = b * h * h * h / 12, Iz = h * b * b * b / 12, J = 1e-5;
const double k = 1.2;  // rectangle

Model timoshenko(json d) {
  d["sections"][0]["ky"] = k;
  d["sections"][0]["kz"] = k;
  Model m = read_model(d);
  m.sections[0].ky = m.sections[0].kz = k;
  for (auto& e : m.elements) e.theory = BeamTheory::Timoshenko;
  for (auto& e : m.members) e.theory = BeamTheory::Timoshenko;
  return m;
}
}  // namespace

// The stiffness analysis of a Timoshenko cantilever's tip inverts its exact compliance:
// C(uz,uz) = L^3/(3 E Iy) + k L/(G A), C(uz,ry) = -L^2/(2 E Iy), C(ry,ry) = L/(E Iy), one element.
TEST(Timoshenko, CantileverTipStiffnessIsTheInverseOfTheExactCompliance) {
  json d = straight_member(L, 1, E, G, A, Iy, Iz, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  const Model m = timoshenko(d);
  const CondensedStiffness s = linear_node_stiffness(m, m.find_node("B"));
  const Mat6 C = s.K.inverse();
  const double czz = L * L * L / (3 * E * Iy) + k * L / (G * A);
  const double cyy = L * L * L / (3 * E * Iz) + k * L / (G * A);
  EXPECT_NEAR(C(2, 2), czz, 1e-9 * czz);
  EXPECT_NEAR(C(1, 1), cyy, 1e-9 * cyy);
  EXPECT_NEAR(C(2, 4), -L * L / (2 * E * Iy), 1e-9 * L * L / (2 * E * Iy));
  EXPECT_NEAR(C(4, 4), L / (E * Iy), 1e-9 * L / (E * Iy));
  EXPECT_GT(k * L / (G * A) / czz, 0.02);  // the shear part is not negligible (3 %)
}

// The co-rotational path uses the Timoshenko local element: under a small tip load (deflection
// 1e-5 L) the tip deflection is the linear Timoshenko one, P L^3/(3 EI) + k P L/(G A), to 1e-5
// (the geometric nonlinearity is of order (v/L)^2).
TEST(Timoshenko, PathFollowingAtSmallLoadGivesTheTimoshenkoDeflection) {
  const double czz = L * L * L / (3 * E * Iy) + k * L / (G * A);
  const double P = 1e-5 * L / czz;
  json d = straight_member(L, 4, E, G, A, Iy, Iz, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 0, 0, P));
  const Model m = timoshenko(d);
  PathOptions o;
  o.increments = 1;
  o.stability = false;
  o.locate_critical = false;
  o.track = {m.find_node("B")};
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  const double w = r.steps.back().track[0][2];
  EXPECT_NEAR(w, P * czz, 1e-5 * P * czz);
}

// A stubby pinned column buckles (about its weak axis, Iz) at Engesser's load P_E/(1 + P_E k/(G A))
// (Timoshenko & Gere, Theory of Elastic Stability, 1961, eq. 2.44). The geometric stiffness is the
// Euler-Bernoulli one (elements/geometric_stiffness.hpp) on the Timoshenko elastic stiffness: its
// nodal rotations are section rotations, not w', which leaves a difference of second order in the
// shear parameter (here P_E k/(G A) = 0.026): the load converges to 1.1e-4 below Engesser's. Must be
// within 3e-4 of it at 16 and 32 elements, while the Euler-Bernoulli load is 2.6 % higher.
TEST(Timoshenko, StubbyPinnedColumnBucklesAtEngessersLoad) {
  const double PE = pi * pi * E * Iz / (L * L);
  const double engesser = PE / (1 + PE * k / (G * A));
  for (int n : {8, 16, 32}) {
    json d = straight_member(L, n, E, G, A, Iy, Iz, J);
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
    d["supports"].push_back(fix("B", {"uy", "uz"}));
    d["loads"].push_back(load("B", -1.0, 0, 0));
    const Model m = timoshenko(d);
    const BucklingResult r = solve_buckling(m);
    ASSERT_EQ(r.status, BucklingStatus::Succeeded) << r.message;
    const double err = r.load_factors[0] / engesser - 1.0;
    std::cout << n << " elements: P_cr = " << r.load_factors[0] << ", Engesser " << engesser << ", Euler " << PE
              << ", relative " << err << "\n";
    if (n >= 16) {
      EXPECT_LT(std::abs(err), 3e-4) << n << " elements";
    }
  }
  EXPECT_GT(PE / engesser - 1.0, 0.02);
}

}  // namespace timoshenko_test
