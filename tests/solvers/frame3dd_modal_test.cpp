// Frame3DD's example D as an external reference for the modal analysis.
//
// Source: Frame3DD (H. P. Gavin), examples/exD.3dd and examples/exD.out, version 20140514+
// (github.com/hpgavin/frame3dd): "dynamic properties of an un-restrained frame with a triangular
// section", 24 nodes, 30 elements, no supports, no shear deformation, no geometric stiffness,
// consistent mass, 14 modes (kip, in, s; density 7.33e-7 kip s^2/in^4). Frame3DD's consistent mass
// is the same matrix as ours (src/frame3dd.c, consistent_M: rho A L/3, 13/35 rho A L + 6 rho I/(5L),
// ...; torsion rho J L/3 where beamfea uses rho (Iy + Iz) L/3: equal here, J = Iy + Iz = 5000; its
// printed diagonal, e.g. node 2: X-mass 7.33000e-3, Y-mass 8.20436e-3, X-inertia 2.93200e-1,
// Y-inertia 3.07441, is reproduced by summing over the node's two elements), and each member is one
// element in both programs.
// Frame3DD finds modes 1-4 at < 2e-6 Hz, modes 5-6 at 0.016 and 0.033 Hz, elastic modes 7-14 at
// 8.780717 ... 31.970096 Hz.
//
// The node radii. exD gives nine nodes a radius r = 10 in. In Frame3DD's source (src/frame3dd_io.c,
// read_frame_element_data: Le[b] = L[b] - r[n1] - r[n2]; src/frame3dd.c, elastic_K: every term of
// the element stiffness uses Le, E A/Le, 12 E I/Le^3 ...; consistent_M: the full L) the radius
// shortens the elastic length of the element, while the coordinate transformation keeps the node
// centres: the rigid-zone terms that would carry the end rotations over the radius (r1 t7 ... in
// src/coordtrans.c, atma) are commented out ("this needs work"). So each member with a radius is
// the beam of length Le stretched between nodes L apart: stiffer (E I/Le^3 instead of E I/L^3), and
// not free under a rigid rotation (the chord turns by theta L/Le where the ends turn by theta), which
// is why Frame3DD's rigid-body modes 5 and 6 are not at zero. beamfea's members without
// "rigid_ends" are elastic over their full length, and its elastic frequencies are 11-13 % lower.
// Verified below by rebuilding Frame3DD's matrices from beamfea's element matrices (stiffness at Le,
// mass at L, transformation without offsets) and solving them: Frame3DD's printed frequencies
// follow to 1e-5. A finite joint modelled physically (rigid links over the radii or "rigid_ends",
// the beam over Le) is stiffer than beamfea's full-length members and softer than Frame3DD's.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <Eigen/Eigenvalues>

#include "elements/beam_mass.hpp"
#include "nl_models.hpp"
#include "solvers/generalized_eigen.hpp"
#include "solvers/modal.hpp"

namespace frame3dd_modal_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double kDensity = 7.33e-7;
// exD.3dd's node radii (in): 10 at nodes 1 3 5 10 12 14 19 21 23.
const double kRadius[24] = {10, 0, 10, 0, 10, 0, 0, 0, 0, 10, 0, 10, 0, 10, 0, 0, 0, 0, 10, 0, 10, 0, 10, 0};
// Frame3DD exD.out, modes 7-14 (Hz).
const double kFrame3dd[8] = {8.780717, 11.625557, 12.435356, 13.326844, 13.577855, 18.934495, 28.440739, 31.970096};

json example_d() {
  const double xyz[24][3] = {{-120, 0, -210}, {0, 0, -210}, {120, 0, -210}, {60, 115, -210}, {0, 230, -210},
                             {-60, 115, -210}, {-120, 0, -90}, {120, 0, -90}, {0, 230, -90}, {-120, 0, 0},
                             {0, 0, 0}, {120, 0, 0}, {60, 115, 0}, {0, 230, 0}, {-60, 115, 0},
                             {-120, 0, 90}, {120, 0, 90}, {0, 230, 90}, {-120, 0, 210}, {0, 0, 210},
                             {120, 0, 210}, {60, 115, 210}, {0, 230, 210}, {-60, 115, 210}};
  const int conn[30][2] = {{1, 2},   {2, 3},   {3, 4},   {4, 5},   {5, 6},   {6, 1},   {1, 7},   {3, 8},
                           {5, 9},   {7, 10},  {8, 12},  {9, 14},  {10, 11}, {11, 12}, {12, 13}, {13, 14},
                           {14, 15}, {15, 10}, {10, 16}, {12, 17}, {14, 18}, {16, 19}, {17, 21}, {18, 23},
                           {19, 20}, {20, 21}, {21, 22}, {22, 23}, {23, 24}, {24, 19}};
  json d;
  d["nodes"] = json::array();
  for (int i = 0; i < 24; ++i) d["nodes"].push_back({{"id", i + 1}, {"xyz", {xyz[i][0], xyz[i][1], xyz[i][2]}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", 29000.0}, {"G", 11500.0}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", 125.0}, {"Iy", 2500.0}, {"Iz", 2500.0}, {"J", 5000.0}}});
  d["elements"] = json::array();
  for (int e = 0; e < 30; ++e)
    d["elements"].push_back({{"id", e + 1}, {"type", "beam"}, {"nodes", {conn[e][0], conn[e][1]}}, {"material", "m"},
                             {"section", "s"}});
  return d;
}
}  // namespace

TEST(Frame3ddExampleD, UnrestrainedFrameHasFrame3ddsMassAndRigidBodyModes) {
  json d = example_d();
  Model m = read_model(d);
  m.materials[0].density = kDensity;
  ModalOptions o;
  o.modes = 14;
  const ModalResult r = solve_modal(m, o);
  ASSERT_EQ(r.status, ModalStatus::Succeeded) << r.message;
  ASSERT_EQ(r.frequencies.size(), 14);
  // Frame3DD exD.out: total mass 3.240350e-01.
  EXPECT_NEAR(r.total_mass[0], 3.240350e-01, 1e-6);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(r.frequencies[k], 0.0) << "mode " << k + 1;
    EXPECT_EQ(r.kinds[static_cast<std::size_t>(k)], ModeKind::RigidBody);
  }
  // beamfea's members are elastic over their full length: 11-13 % below Frame3DD (see the header).
  for (int k = 0; k < 8; ++k) {
    const double f = r.frequencies[6 + k];
    std::cout << "mode " << 7 + k << ": " << f << " Hz, Frame3DD " << kFrame3dd[k] << ", ratio " << f / kFrame3dd[k] << "\n";
    EXPECT_EQ(r.kinds[static_cast<std::size_t>(6 + k)], ModeKind::Elastic);
    EXPECT_GT(f / kFrame3dd[k], 0.85);
    EXPECT_LT(f / kFrame3dd[k], 0.90);
  }
}

// Frame3DD's matrices rebuilt from beamfea's elements: each member's local stiffness at the elastic
// length Le = L - r1 - r2 (src/frame3dd.c, elastic_K), its consistent mass at L (consistent_M), both
// turned to global axes without rigid offsets (src/coordtrans.c, atma), assembled over the 144 DOFs
// of the free frame. Solved densely (Eigen's generalized self-adjoint solver) and by beamfea's
// shift-invert eigen-solver: modes 7-14 equal Frame3DD's printed frequencies to 1e-5 (its output
// has 7 figures; both programs' matrices agree to rounding), and its two "rigid" modes at 0.016 and
// 0.033 Hz come out too, to its 6 decimals (the shortened elements resist a rigid rotation). This is
// the whole of the 11-13 % difference.
TEST(Frame3ddExampleD, Frame3ddFrequenciesFollowFromTheElasticLengthShortenedByTheNodeRadii) {
  const Model m = read_model(example_d());
  const int n = 6 * static_cast<int>(m.nodes.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  for (const auto& el : m.elements) {
    const int n1 = el.nodes[0], n2 = el.nodes[1];
    const Vec3 &x1 = m.nodes[n1].x, &x2 = m.nodes[n2].x;
    const double L = (x2 - x1).norm(), Le = L - kRadius[n1] - kRadius[n2];
    const BeamSection s{29000.0, 11500.0, 125.0, 2500.0, 2500.0, 5000.0};
    const Mat12 T = beam_transformation(beam_local_axes(x1, x2, el.orientation));
    const Mat12 ke = T.transpose() * beam_local_stiffness(s, Le) * T;
    const Mat12 me = T.transpose() * beam_local_mass(s, kDensity, L, MassKind::Consistent) * T;
    for (int a = 0; a < 12; ++a)
      for (int b = 0; b < 12; ++b) {
        const int i = 6 * (a < 6 ? n1 : n2) + a % 6, j = 6 * (b < 6 ? n1 : n2) + b % 6;
        K(i, j) += ke(a, b);
        M(i, j) += me(a, b);
      }
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  ASSERT_EQ(es.info(), Eigen::Success);
  const Eigen::VectorXd w2 = es.eigenvalues();
  // beamfea's eigen-solver on the same pencil (sparse; dense below 600 DOFs).
  const GeneralizedEigenPairs gp = nearest_generalized_eigenpairs(K.sparseView(), M.sparseView(), 14, -1e-3);
  ASSERT_TRUE(gp.converged) << gp.message;
  ASSERT_EQ(gp.values.size(), 14);
  for (int k = 0; k < 14; ++k) {
    const double f = std::sqrt(std::max(0.0, w2[k])) / (2 * pi);
    const double fb = std::sqrt(std::max(0.0, gp.values[k])) / (2 * pi);
    std::cout << "Frame3DD's matrices, mode " << k + 1 << ": " << f << " Hz (beamfea's solver " << fb << ")"
              << (k >= 6 ? " Frame3DD " + std::to_string(kFrame3dd[k - 6]) : std::string()) << "\n";
    if (k == 4 || k == 5) {  // Frame3DD: 0.015974, 0.033069 Hz (6 decimals)
      EXPECT_NEAR(f, k == 4 ? 0.015974 : 0.033069, 1e-6) << "mode " << k + 1;
    } else if (k < 4) {
      EXPECT_LT(f, 1e-5) << "mode " << k + 1;  // Frame3DD: < 2e-6 Hz
    }
    if (k >= 6) {
      EXPECT_NEAR(f, kFrame3dd[k - 6], 1e-5 * kFrame3dd[k - 6]) << "mode " << k + 1;
      EXPECT_NEAR(fb, kFrame3dd[k - 6], 1e-5 * kFrame3dd[k - 6]) << "mode " << k + 1;
    }
  }
}

// A finite joint modelled physically: at each node with a radius, the member's end is moved in by
// r along the member and tied to the node by a rigid link; the beam (stiffness and mass) spans Le,
// the rigid zones are massless. The frame stays free under rigid motions (six zero modes, where
// Frame3DD's shortened elements give two at 0.016 and 0.033 Hz), and it is stiffer and lighter
// than the full-length frame, so every elastic frequency is higher. It is not Frame3DD's model:
// modes 7-12 come out 2-5 % above Frame3DD's, modes 13-14 7-10 % below (printed). The members'
// "rigid_ends" state the same joints and give the same frequencies.
TEST(Frame3ddExampleD, RigidJointZonesOverTheRadiiStiffenTheFrameButAreNotFrame3ddsModel) {
  json d = example_d();
  const json full = d;
  d["elements"] = json::array();
  int extra = 0;
  for (const auto& e : full["elements"]) {
    std::array<json, 2> ends{e["nodes"][0], e["nodes"][1]};
    const int i1 = ends[0].get<int>() - 1, i2 = ends[1].get<int>() - 1;
    const Vec3 x1(full["nodes"][i1]["xyz"][0].get<double>(), full["nodes"][i1]["xyz"][1].get<double>(),
                  full["nodes"][i1]["xyz"][2].get<double>());
    const Vec3 x2(full["nodes"][i2]["xyz"][0].get<double>(), full["nodes"][i2]["xyz"][1].get<double>(),
                  full["nodes"][i2]["xyz"][2].get<double>());
    const Vec3 ex = (x2 - x1).normalized();
    std::array<json, 2> beam_ends = ends;
    for (int k = 0; k < 2; ++k) {
      const int node = k == 0 ? i1 : i2;
      if (kRadius[node] == 0.0) continue;
      const Vec3 y = k == 0 ? Vec3(x1 + kRadius[node] * ex) : Vec3(x2 - kRadius[node] * ex);
      const std::string id = name("Z", ++extra);
      d["nodes"].push_back({{"id", id}, {"xyz", {y.x(), y.y(), y.z()}}});
      d["elements"].push_back({{"id", name("R", extra)}, {"type", "rigid"}, {"nodes", {ends[k], id}}});
      beam_ends[k] = id;
    }
    json b = e;
    b["nodes"] = {beam_ends[0], beam_ends[1]};
    d["elements"].push_back(b);
  }
  Model zones = read_model(d), plain = read_model(full);
  zones.materials[0].density = plain.materials[0].density = kDensity;
  ModalOptions o;
  o.modes = 14;
  const ModalResult rz = solve_modal(zones, o), rp = solve_modal(plain, o);
  ASSERT_EQ(rz.status, ModalStatus::Succeeded) << rz.message;
  ASSERT_EQ(rp.status, ModalStatus::Succeeded) << rp.message;
  for (int k = 0; k < 6; ++k) EXPECT_EQ(rz.kinds[static_cast<std::size_t>(k)], ModeKind::RigidBody);
  for (int k = 6; k < 14; ++k) {
    std::cout << "mode " << k + 1 << ": full length " << rp.frequencies[k] << ", rigid zones " << rz.frequencies[k]
              << ", Frame3DD " << kFrame3dd[k - 6] << " Hz\n";
    EXPECT_GT(rz.frequencies[k], rp.frequencies[k]) << "mode " << k + 1;
  }
  // The same finite joints stated by "rigid_ends" (rigid arms inside the elements,
  // elements/offset_element.hpp, instead of rigid links between extra nodes): the same frame.
  json arms = full;
  for (auto& e : arms["elements"]) {
    const int i1 = e["nodes"][0].get<int>() - 1, i2 = e["nodes"][1].get<int>() - 1;
    if (kRadius[i1] > 0.0 || kRadius[i2] > 0.0) e["rigid_ends"] = {kRadius[i1], kRadius[i2]};
  }
  Model with_arms = read_model(arms);
  with_arms.materials[0].density = kDensity;
  const ModalResult ra = solve_modal(with_arms, o);
  ASSERT_EQ(ra.status, ModalStatus::Succeeded) << ra.message;
  for (int k = 0; k < 6; ++k) EXPECT_EQ(ra.kinds[static_cast<std::size_t>(k)], ModeKind::RigidBody);
  for (int k = 6; k < 14; ++k) EXPECT_NEAR(ra.frequencies[k], rz.frequencies[k], 1e-8 * rz.frequencies[k]) << "mode " << k + 1;
}

// Frame3DD's example B (examples/exB.3dd, exB.out; N, mm, ton): a pyramid of four one-element
// members from the apex node 1 to four clamped base nodes, shear deformation ON (A = 36, Asy = Asz
// = 20 mm^2), geometric stiffness ON, a 0.1 ton extra mass at node 1, consistent mass, 6 modes
// (18.807943, 19.105451, 19.690439, 31.711570, 35.159165, 42.248953 Hz). Frame3DD's modal stiffness
// is K_e + K_g of its LAST static load case (src/main.c: the K left by the load-case loop), here
// case 3 (self-weight and two internal point loads), with the axial force T = -Q[1] at each
// element's first node (src/frame3dd.c, assemble_K), printed in exB.out: 75.494, 74.048, 20.717,
// 22.163 N compression. Its K_g (geometric_K) is the consistent one with shear-modified
// coefficients, T/L (1.2 + 2 Phi + Phi^2)/(1 + Phi)^2 ..., torsion T/L J/A; its consistent mass
// ignores shear and takes the torsional inertia from J (rho J L/3, J = 1000; beamfea: Iy + Iz = 984).
// Rebuilt here: beamfea's Timoshenko local stiffness (it must equal Frame3DD's elastic_K with
// shear), Frame3DD's K_g formula with the printed T, beamfea's Euler-Bernoulli consistent mass
// corrected to rho J L/3 in torsion, the extra mass on node 1's translations; the base DOFs
// eliminated (Frame3DD holds them with large terms: its base nodes move ~1e-9). Asserted: the mass
// diagonal of node 1 equals Frame3DD's printed one to 1e-5, and the six frequencies (below).
// Observed: modes 1-3 agree to ~9.5e-6, modes 4-6 to ~1.5e-7; the 1e-5 residue of modes 1-3 is
// not explained. Tolerances 2e-5 (modes 1-3) and 1e-6 (modes 4-6). Dropping the shear moves modes
// 1-3 by 8.9e-5 (> 3 tolerances), dropping K_g moves modes 4-6 by 9e-6 ... 6.7e-5 (> 5
// tolerances) and modes 1-3 by 2-3 %: asserted below, so the check sees both options.
constexpr double kExampleBTolerance[2] = {2e-5, 1e-6};
TEST(Frame3ddExampleB, ShearAndGeometricStiffnessPyramidFrequenciesFromRebuiltMatrices) {
  const Vec3 X[5] = {{0, 0, 1000}, {-1200, -900, 0}, {1200, -900, 0}, {1200, 900, 0}, {-1200, 900, 0}};
  const int conn[4][2] = {{1, 0}, {0, 2}, {0, 3}, {4, 0}};  // 0-based: elements 2-1, 1-3, 1-4, 5-1
  const double T[4] = {-75.494, -74.048, -20.717, -22.163};  // tension positive
  const double E = 200000, G = 79300, A = 36, As = 20, J = 1000, I = 492, rho = 7.85e-9, m_extra = 0.1;
  // K and M over node 1's six DOFs; `shear` and `geometric` switch Frame3DD's two options.
  auto assemble = [&](bool shear, bool geometric, Eigen::MatrixXd& K, Eigen::MatrixXd& M) {
    K = Eigen::MatrixXd::Zero(6, 6);
    M = Eigen::MatrixXd::Zero(6, 6);
    for (int e = 0; e < 4; ++e) {
      const Vec3 &x1 = X[conn[e][0]], &x2 = X[conn[e][1]];
      const double L = (x2 - x1).norm();
      BeamSection s{E, G, A, I, I, J};
      const Mat12 mloc = [&] {
        Mat12 m = beam_local_mass(s, rho, L, MassKind::Consistent);  // Euler-Bernoulli: Asy = Asz = 0
        const double dp = rho * (J - (I + I)) * L;                     // torsion: rho J L [1/3 1/6; 1/6 1/3]
        m(3, 3) += dp / 3;
        m(9, 9) += dp / 3;
        m(3, 9) += dp / 6;
        m(9, 3) += dp / 6;
        return m;
      }();
      if (shear) s.Asy = s.Asz = As;
      Mat12 kg = Mat12::Zero();
      const double phi = shear ? 12 * E * I / (G * As * L * L) : 0.0, D = (1 + phi) * (1 + phi);
      const double t = geometric ? T[e] : 0.0;
      const double a = t / L * (1.2 + 2 * phi + phi * phi) / D, b = t * L * (2.0 / 15 + phi / 6 + phi * phi / 12) / D;
      const double c = -t * L * (1.0 / 30 + phi / 6 + phi * phi / 12) / D, d = t / 10 / D;
      // Frame3DD's geometric_K (1-based there): v = 2, 8; w = 3, 9; rx = 4, 10; ry = 5, 11; rz = 6, 12.
      for (int p : {1, 2}) {
        kg(p, p) = kg(p + 6, p + 6) = a;
        kg(p, p + 6) = kg(p + 6, p) = -a;
      }
      kg(3, 3) = kg(9, 9) = t / L * J / A;
      kg(3, 9) = kg(9, 3) = -t / L * J / A;
      for (int p : {4, 5}) {
        kg(p, p) = kg(p + 6, p + 6) = b;
        kg(p, p + 6) = kg(p + 6, p) = c;
      }
      kg(4, 2) = kg(2, 4) = kg(10, 2) = kg(2, 10) = -d;
      kg(8, 4) = kg(4, 8) = kg(10, 8) = kg(8, 10) = d;
      kg(5, 1) = kg(1, 5) = kg(11, 1) = kg(1, 11) = d;
      kg(7, 5) = kg(5, 7) = kg(11, 7) = kg(7, 11) = -d;
      const Mat12 Tr = beam_transformation(beam_local_axes(x1, x2, Vec3(0, 0, 1)));
      const Mat12 ke = Tr.transpose() * (beam_local_stiffness(s, L) + kg) * Tr;
      const Mat12 me = Tr.transpose() * mloc * Tr;
      const int off = conn[e][0] == 0 ? 0 : 6;  // node 1's block in the element
      K += ke.block<6, 6>(off, off);
      M += me.block<6, 6>(off, off);
    }
    for (int k = 0; k < 3; ++k) M(k, k) += m_extra;
  };
  auto frequencies = [&](bool shear, bool geometric) {
    Eigen::MatrixXd K, M;
    assemble(shear, geometric, K, M);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    return Eigen::VectorXd(es.eigenvalues().cwiseSqrt() / (2 * pi));
  };
  Eigen::MatrixXd K, M;
  assemble(true, true, K, M);
  // exB.out, "N O D A L   M A S S E S", node 1.
  const double printed[6] = {1.00723e-01, 1.00738e-01, 1.00733e-01, 3.51392e+01, 4.73634e+01, 4.36768e+01};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(M(k, k), printed[k], 1e-5 * printed[k]) << "mass diagonal " << k;
  const Eigen::VectorXd f = frequencies(true, true);
  const Eigen::VectorXd no_shear = frequencies(false, true), no_kg = frequencies(true, false);
  const double frame3dd[6] = {18.807943, 19.105451, 19.690439, 31.711570, 35.159165, 42.248953};
  double shear_effect = 0.0, kg_effect = 0.0;
  for (int k = 0; k < 6; ++k) {
    std::cout << "exB mode " << k + 1 << ": " << f[k] << " Hz, Frame3DD " << frame3dd[k] << ", relative "
              << f[k] / frame3dd[k] - 1 << "; without shear " << no_shear[k] / frame3dd[k] - 1 << ", without K_g "
              << no_kg[k] / frame3dd[k] - 1 << "\n";
    const double tol = kExampleBTolerance[k < 3 ? 0 : 1];
    EXPECT_NEAR(f[k], frame3dd[k], tol * frame3dd[k]) << "mode " << k + 1;
    if (k < 3) shear_effect = std::max(shear_effect, std::abs(no_shear[k] / frame3dd[k] - 1) / tol);
    kg_effect = std::max(kg_effect, std::abs(no_kg[k] / frame3dd[k] - 1) / tol);
    if (k >= 3) {
      EXPECT_GT(std::abs(no_kg[k] / frame3dd[k] - 1), 5 * tol) << "mode " << k + 1;
    }
  }
  // The check sees both options: dropping either moves frequencies by several tolerances.
  EXPECT_GT(shear_effect, 3.0);
  EXPECT_GT(kg_effect, 5.0);
}

}  // namespace frame3dd_modal_test
