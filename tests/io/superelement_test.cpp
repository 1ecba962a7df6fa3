// The superelement analysis (solvers/superelement.hpp): Guyan and Craig-Bampton reductions checked
// against closed forms (cantilever tip stiffness and consistent mass, the unit-load compliance of an
// L-shaped bracket), the convergence of Craig-Bampton frequencies, free-free rigid-body modes, and
// the program's files and bad-input exits.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "solvers/modal.hpp"
#include "solvers/superelement.hpp"
#include "support/cli_case.hpp"
#include "support/files.hpp"

namespace superelement_test {

namespace {

using nlohmann::json;
using beamfea::Mat6;
using beamfea::Vec3;

constexpr double E = 2.1e11, G = 8.0e10, rho = 7850.0;

// A straight cantilever along x from A (clamped unless `clamped` is false) to B, `divisions`
// elements, rectangular section properties given directly.
json cantilever(double L, int divisions, bool clamped = true, const std::string& theory = "euler_bernoulli") {
  json d = {{"nodes", {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L, 0, 0}}}}},
            {"materials", {{{"id", "s"}, {"E", E}, {"G", G}, {"density", rho}}}},
            {"sections", {{{"id", "r"}, {"A", 2e-3}, {"Iy", 3e-7}, {"Iz", 5e-7}, {"J", 4e-7}, {"ky", 1.2}, {"kz", 1.2}}}},
            {"elements",
             {{{"id", "e"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "s"}, {"section", "r"},
               {"orientation", {0, 0, 1}}, {"divisions", divisions}, {"theory", theory}}}},
            {"analyses", json::array()}};
  if (clamped) d["supports"] = {{{"node", "A"}, {"fix", "all"}}};
  return d;
}

beamfea::SuperelementResult reduce(const json& doc, const std::vector<std::string>& interface, int modes = 0) {
  const beamfea::Model m = beamfea::read_model(doc);
  std::vector<int> nodes;
  for (const auto& id : interface) nodes.push_back(m.find_node(id));
  beamfea::SuperelementOptions o;
  o.modes = modes;
  return beamfea::reduce_superelement(m, nodes, o);
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

// The closed-form compliance of a cantilever of length L along the unit vector e, at its free end,
// for a section with equal bending stiffness about every transverse axis (EI), in global axes:
// u = L/(EA) e e^T F + L^3/(3EI) (I - e e^T) F + L^2/(2EI) M x e, theta = L^2/(2EI) e x F +
// (L/(GJ) e e^T + L/(EI) (I - e e^T)) M (the unit-load method: Gere & Timoshenko, "Mechanics of
// Materials", cantilever deflection tables).
Mat6 round_cantilever_compliance(const Vec3& e, double L, double EA, double EI, double GJ) {
  const Eigen::Matrix3d P = e * e.transpose(), Q = Eigen::Matrix3d::Identity() - P;
  Eigen::Matrix3d ex;
  ex << 0, -e.z(), e.y(), e.z(), 0, -e.x(), -e.y(), e.x(), 0;
  Mat6 C;
  C.topLeftCorner<3, 3>() = L / EA * P + L * L * L / (3 * EI) * Q;
  C.bottomLeftCorner<3, 3>() = L * L / (2 * EI) * ex;
  C.topRightCorner<3, 3>() = C.bottomLeftCorner<3, 3>().transpose();
  C.bottomRightCorner<3, 3>() = L / GJ * P + L / EI * Q;
  return C;
}

// The rigid transport of a wrench at `to` back to `from` (F unchanged, M + (to - from) x F), whose
// transpose carries the motion of `from` to `to` (u + theta x r, theta).
Mat6 transport(const Vec3& r) {
  Eigen::Matrix3d rx;
  rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  Mat6 T = Mat6::Identity();
  T.bottomLeftCorner<3, 3>() = rx;
  return T;
}

}  // namespace

// Guyan onto the tip of a clamped cantilever: the exact static tip stiffness (the end-2 block of the
// Euler-Bernoulli member: 12EI/L^3, 6EI/L^2, 4EI/L, EA/L, GJ/L; Przemieniecki, "Theory of Matrix
// Structural Analysis", eq. 5.115), whatever the number of elements inside.
TEST(Superelement, GuyanOfClampedCantileverIsTheExactTipStiffness) {
  const double L = 1.3, A = 2e-3, Iy = 3e-7, Iz = 5e-7, J = 4e-7;
  const auto r = reduce(cantilever(L, 5), {"B"});
  ASSERT_EQ(r.status, beamfea::SuperelementStatus::Succeeded) << r.message;
  Mat6 K = Mat6::Zero();
  K(0, 0) = E * A / L;
  K(1, 1) = 12 * E * Iz / (L * L * L), K(1, 5) = K(5, 1) = -6 * E * Iz / (L * L), K(5, 5) = 4 * E * Iz / L;
  K(2, 2) = 12 * E * Iy / (L * L * L), K(2, 4) = K(4, 2) = 6 * E * Iy / (L * L), K(4, 4) = 4 * E * Iy / L;
  K(3, 3) = G * J / L;
  ASSERT_EQ(r.stiffness.rows(), 6);
  EXPECT_LT(relative(r.stiffness, K), 1e-9);
  EXPECT_TRUE(r.rigid_body_modes.empty());
}

// With one element the interface is the element's end: the reduced mass is the end-2 block of the
// consistent mass matrix: rho A L/420 [156 -22L; -22L 4L^2] plus the rotary part rho I/(30 L)
// [36 -3L; -3L 4L^2] in the x-y plane (theta = rz; x-z: theta = -ry), rho A L/3 axial and
// rho (Iy + Iz) L/3 torsion (Przemieniecki 1968, eqs. 11.18 and 11.41).
TEST(Superelement, GuyanMassOfOneElementIsTheConsistentEndBlock) {
  const double L = 0.8, A = 2e-3, Iy = 3e-7, Iz = 5e-7;
  const auto r = reduce(cantilever(L, 1), {"B"});
  ASSERT_EQ(r.status, beamfea::SuperelementStatus::Succeeded) << r.message;
  ASSERT_TRUE(r.has_mass);
  const double m = rho * A * L;
  Mat6 M = Mat6::Zero();
  M(0, 0) = m / 3;
  M(1, 1) = m * 156 / 420 + 36 * rho * Iz / (30 * L);
  M(2, 2) = m * 156 / 420 + 36 * rho * Iy / (30 * L);
  M(3, 3) = rho * (Iy + Iz) * L / 3;
  M(4, 4) = m * 4 * L * L / 420 + 4 * L * rho * Iy / 30;
  M(5, 5) = m * 4 * L * L / 420 + 4 * L * rho * Iz / 30;
  M(1, 5) = M(5, 1) = -m * 22 * L / 420 - 3 * rho * Iz / 30;
  M(2, 4) = M(4, 2) = m * 22 * L / 420 + 3 * rho * Iy / 30;
  EXPECT_LT(relative(r.mass, M), 1e-9);
}

// An L-shaped bracket of two legs (A-B along x, B-C along y), clamped at A: its Guyan stiffness at C
// is the inverse of the unit-load compliance over both legs (axial, both bending planes, torsion).
TEST(Superelement, LBracketCondensesToTheInverseOfTheUnitLoadCompliance) {
  const double L1 = 0.6, L2 = 0.35;
  const double A1 = 3e-4, I1 = 2e-8, J1 = 4e-8;  // round sections: I about every transverse axis
  const double A2 = 2e-4, I2 = 1e-8, J2 = 2e-8;
  json d = {{"nodes", {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L1, 0, 0}}}, {{"id", "C"}, {"xyz", {L1, L2, 0}}}}},
            {"materials", {{{"id", "s"}, {"E", E}, {"G", G}}}},
            {"sections", {{{"id", "p1"}, {"A", A1}, {"Iy", I1}, {"Iz", I1}, {"J", J1}}, {{"id", "p2"}, {"A", A2}, {"Iy", I2}, {"Iz", I2}, {"J", J2}}}},
            {"elements",
             {{{"id", "leg1"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "s"}, {"section", "p1"}, {"divisions", 3}},
              {{"id", "leg2"}, {"type", "beam"}, {"nodes", {"B", "C"}}, {"material", "s"}, {"section", "p2"}, {"divisions", 2}}}},
            {"supports", {{{"node", "A"}, {"fix", "all"}}}},
            {"analyses", json::array()}};
  const auto r = reduce(d, {"C"});
  ASSERT_EQ(r.status, beamfea::SuperelementStatus::Succeeded) << r.message;
  const Vec3 a(0, 0, 0), b(L1, 0, 0), c(L1, L2, 0);
  // Compliance at C: each leg's own compliance at its end, carried rigidly to C (the wrench at C
  // seen at the leg's end, the leg end's motion carried to C).
  const Mat6 C = transport(c - b).transpose() * round_cantilever_compliance(Vec3::UnitX(), L1, E * A1, E * I1, G * J1) *
                     transport(c - b) +
                 round_cantilever_compliance(Vec3::UnitY(), L2, E * A2, E * I2, G * J2);
  (void)a;
  EXPECT_LT(relative(r.stiffness, C.inverse()), 1e-9);
}

// Craig-Bampton: the reduced model's lowest frequencies approach the full model's from above,
// monotonically as fixed-interface modes are added, and equal them when all are kept.
TEST(Superelement, CraigBamptonFrequenciesConvergeFromAboveMonotonically) {
  json d = cantilever(1.0, 12);
  const beamfea::Model m = beamfea::read_model(d);
  beamfea::ModalOptions mo;
  mo.modes = 3;
  const auto full = beamfea::solve_modal(m, mo);
  ASSERT_EQ(full.status, beamfea::ModalStatus::Succeeded) << full.message;
  auto lowest = [&](int modes) {
    const auto r = reduce(d, {"B"}, modes);
    EXPECT_EQ(r.status, beamfea::SuperelementStatus::Succeeded) << r.message;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(r.stiffness, r.mass);
    Eigen::Vector3d f;
    for (int k = 0; k < 3; ++k) f[k] = std::sqrt(es.eigenvalues()[k]) / (2 * std::numbers::pi);
    return f;
  };
  Eigen::Vector3d previous = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const int modes : {1, 2, 4, 8, 16, 32}) {
    const Eigen::Vector3d f = lowest(modes);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(f[k], full.frequencies[k] * (1 - 1e-9)) << modes << " modes, frequency " << k;
      EXPECT_LE(f[k], previous[k] * (1 + 1e-9)) << modes << " modes, frequency " << k;
    }
    previous = f;
  }
  // Every fixed-interface mode (6 x 11 interior DOFs): the reduction is exact.
  const Eigen::Vector3d f = lowest(66);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k] / full.frequencies[k], 1.0, 1e-6);
}

// The fixed-interface frequencies of a cantilever held at both ends are those of a clamped-clamped
// beam: f1 = (4.7300^2 / 2 pi) sqrt(E I / (rho A L^4)) (Blevins, "Formulas for Natural Frequency and
// Mode Shape", table 8-1), for the weaker plane (Iy). The beam is slender (L / r = 400): the consistent
// mass's rotary inertia lowers f1 by about (beta r / L)^2 / 2 = 7e-5, within the tolerance.
TEST(Superelement, FixedInterfaceFrequencyIsTheClampedClampedBeams) {
  const double L = 5.0, A = 2e-3, Iy = 3e-7;
  json d = cantilever(L, 16);
  const auto r = reduce(d, {"B"}, 1);
  ASSERT_EQ(r.status, beamfea::SuperelementStatus::Succeeded) << r.message;
  ASSERT_EQ(r.frequencies.size(), 1);
  const double beta = 4.730040745;
  const double f1 = beta * beta / (2 * std::numbers::pi) * std::sqrt(E * Iy / (rho * A * L * L * L * L));
  EXPECT_NEAR(r.frequencies[0] / f1, 1.0, 2e-4);
  EXPECT_EQ(r.stiffness.rows(), 7);
}

// A free-free beam with both ends as the interface: six rigid-body modes are reported (not a
// failure), and they are motions the reduced stiffness does not resist.
TEST(Superelement, FreeFreeBeamReportsSixRigidBodyModes) {
  const auto r = reduce(cantilever(1.0, 4, false), {"A", "B"});
  ASSERT_EQ(r.status, beamfea::SuperelementStatus::Succeeded) << r.message;
  ASSERT_EQ(r.rigid_body_modes.size(), 6u);
  for (const auto& v : r.rigid_body_modes) {
    ASSERT_EQ(v.size(), 12);
    EXPECT_LT((r.stiffness * v).norm(), 1e-9 * r.stiffness.norm() * v.norm());
  }
  // A rigid translation along y is among them: it lies in their span.
  Eigen::MatrixXd R(12, 6);
  for (int k = 0; k < 6; ++k) R.col(k) = r.rigid_body_modes[static_cast<std::size_t>(k)];
  Eigen::VectorXd ty = Eigen::VectorXd::Zero(12);
  ty[1] = ty[7] = 1.0;
  const Eigen::VectorXd fit = R * R.colPivHouseholderQr().solve(ty);
  EXPECT_LT((fit - ty).norm(), 1e-9);
}

// Two interface nodes that a rigid link ties (B, and C carried by B): the interface rows are
// dependent (the saddle-point route). The reduced stiffness acts on the motions the interface can make,
// d = (d_B, the rigid carry of d_B to C), with the energy of the cantilever's exact tip stiffness at B;
// the fixed-interface modes are those of the interface B alone (holding B holds C).
TEST(Superelement, RigidlyTiedInterfaceNodesReduceOnTheirCommonMotion) {
  const double L = 1.3;
  json d = cantilever(L, 5);
  d["nodes"].push_back({{"id", "C"}, {"xyz", {L, 0.2, 0.1}}});
  d["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"B", "C"}}});
  const auto both = reduce(d, {"B", "C"}, 2);
  ASSERT_EQ(both.status, beamfea::SuperelementStatus::Succeeded) << both.message;
  const auto alone = reduce(cantilever(L, 5), {"B"}, 2);
  ASSERT_EQ(alone.status, beamfea::SuperelementStatus::Succeeded) << alone.message;
  ASSERT_EQ(both.stiffness.rows(), 14);
  const Mat6 carry = transport(Vec3(0, 0.2, 0.1)).transpose();  // motion of B -> motion of C
  for (int k = 0; k < 6; ++k) {
    beamfea::Vec6 dB = beamfea::Vec6::Zero();
    dB[k] = 1.0;
    dB[(k + 2) % 6] = 0.5;
    Eigen::VectorXd dd = Eigen::VectorXd::Zero(14);
    dd.head(6) = dB;
    dd.segment(6, 6) = carry * dB;
    const double expected = dB.dot(alone.stiffness.topLeftCorner(6, 6) * dB);
    EXPECT_NEAR(dd.dot(both.stiffness * dd) / expected, 1.0, 1e-9) << k;
  }
  for (int j = 0; j < 2; ++j) EXPECT_NEAR(both.frequencies[j] / alone.frequencies[j], 1.0, 1e-8) << j;
}

// Through the program: results, the .json and .npz files (a ZIP whose "stiffness.npy" holds the
// 6x6 matrix), and a sub-structure of listed elements.
TEST(Superelement, ProgramWritesResultsJsonAndNpz) {
  json d = cantilever(1.3, 5);
  d["analyses"] = {{{"id", "se"}, {"type", "superelement"}, {"interface", {"B"}}, {"elements", {"e"}}}};
  const auto c = beamfea::test::run_model("superelement_files", d);
  ASSERT_EQ(c.code, 0) << c.message;
  const json a = c.results()["analyses"]["se"];
  EXPECT_EQ(a["status"], "ok");
  EXPECT_EQ(a["interface"], json({"B"}));
  EXPECT_EQ(a["stiffness"].size(), 6u);
  EXPECT_NEAR(a["stiffness"][3][3].get<double>(), G * 4e-7 / 1.3, 1e-9 * G * 4e-7 / 1.3);
  EXPECT_TRUE(std::filesystem::exists(c.out() / "se_superelement.json"));
  const std::string npz = beamfea::test::read_text(c.out() / "se_superelement.npz");
  ASSERT_GT(npz.size(), 2 * 6 * 6 * 8u);
  EXPECT_EQ(npz.substr(0, 4), std::string("PK\x03\x04", 4));
  EXPECT_NE(npz.find("stiffness.npy"), std::string::npos);
  EXPECT_NE(npz.find("mass.npy"), std::string::npos);
}

TEST(Superelement, UnknownInterfaceNodeIsBadInput) {
  json d = cantilever(1.0, 2);
  d["analyses"] = {{{"id", "se"}, {"type", "superelement"}, {"interface", {"B", "Q"}}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("superelement_node", d), {"/analyses/0/interface/1", "unknown node 'Q'"});
}

TEST(Superelement, UnknownElementIsBadInput) {
  json d = cantilever(1.0, 2);
  d["analyses"] = {{{"id", "se"}, {"type", "superelement"}, {"interface", {"B"}}, {"elements", {"e", "f"}}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("superelement_element", d), {"/analyses/0/elements/1", "unknown element 'f'"});
}

}  // namespace superelement_test
