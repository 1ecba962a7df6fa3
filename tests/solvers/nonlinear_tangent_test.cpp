// Kinematics and consistent tangent of the nonlinear structure (solvers/nonlinear_structure.hpp):
// rigid links and joints at large rotation, against finite differences of the residual.
#include <gtest/gtest.h>

#include <random>

#include "core/errors.hpp"
#include "solvers/nonlinear_structure.hpp"
#include "solvers/path_following.hpp"
#include "nl_models.hpp"

namespace nonlinear_tangent_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {

// A spatial mechanism-like frame: fixed base -> revolute (z) -> rigid link -> universal (y, x) ->
// beam -> virtual spring (6 coordinates, full stiffness) -> rigid link -> spherical -> beam. The
// universal and the spherical joints are written from their far node, so that the forest meets
// them from nodes[1] (inverted kinematics).
json jointed_frame() {
  json d;
  d["nodes"] = json::array({{{"id", "B"}, {"xyz", {0, 0, 0}}},     {{"id", "B1"}, {"xyz", {0, 0, 0}}},
                            {{"id", "C"}, {"xyz", {0.4, 0.1, 0}}},  {{"id", "C1"}, {"xyz", {0.4, 0.1, 0}}},
                            {{"id", "D"}, {"xyz", {0.9, 0.2, 0.1}}}, {{"id", "D1"}, {"xyz", {0.9, 0.2, 0.1}}},
                            {{"id", "E"}, {"xyz", {1.1, 0.5, 0.2}}}, {{"id", "E1"}, {"xyz", {1.1, 0.5, 0.2}}},
                            {{"id", "F"}, {"xyz", {1.5, 0.6, 0.0}}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", 2e5}, {"G", 8e4}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", 1e-2}, {"Iy", 2e-5}, {"Iz", 1e-5}, {"J", 3e-5}}});
  d["elements"] = json::array(
      {{{"id", "r1"}, {"type", "rigid"}, {"nodes", {"B1", "C"}}},
       {{"id", "b1"}, {"type", "beam"}, {"nodes", {"C1", "D"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}},
       {{"id", "r2"}, {"type", "rigid"}, {"nodes", {"D1", "E"}}},
       {{"id", "b2"}, {"type", "beam"}, {"nodes", {"E1", "F"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}}});
  json K = json::array();
  for (int i = 0; i < 6; ++i) {
    json row = json::array();
    for (int j = 0; j < 6; ++j) row.push_back(i == j ? (i < 3 ? 50.0 : 3.0) : (std::abs(i - j) == 3 ? 0.5 : 0.0));
    K.push_back(row);
  }
  d["joints"] = json::array(
      {{{"id", "j1"}, {"type", "revolute"}, {"nodes", {"B", "B1"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {2.0}}},
       {{"id", "j2"}, {"type", "universal"}, {"nodes", {"C1", "C"}}, {"axes", {{0, 1, 0}, {1, 0, 0}}}, {"stiffness", {1.0, 0.0}}},
       {{"id", "j3"}, {"type", "virtual_spring"}, {"nodes", {"D", "D1"}}, {"axes", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
        {"stiffness", K}},
       {{"id", "j4"}, {"type", "spherical"}, {"nodes", {"E1", "E"}}, {"axes", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}});
  d["supports"] = json::array({fix("B", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array({load("F", 0.3, -0.2, 0.5, 0.05, 0.02, -0.03), load("E", 0.1, 0.2, -0.1, 0.0, 0.04, 0.0)});
  return d;
}

}  // namespace

// The tangent (element tangents through T plus the constraint curvature G) is the derivative of the
// residual r = T^T (f_int - f_app) along the increments of the independent coordinates, at a
// state with large rotations in every joint (0.5 to 1.5 rad) and a deformed beam.
TEST(NonlinearStructure, TangentMatchesFiniteDifferenceOfResidualWithJointsAndRigidLinks) {
  const Model m = read_model(jointed_frame());
  const NonlinearStructure ns(m);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd d(ns.size());
  for (int i = 0; i < ns.size(); ++i) d[i] = (ns.is_rotation(i) ? 1.2 : 0.05) * U(rng);
  // Supported base: no motion there.
  for (int i = 0; i < ns.size(); ++i)
    if (ns.gens()[i].kind != NonlinearStructure::GenKind::JointScalar &&
        ns.gens()[i].kind != NonlinearStructure::GenKind::JointSpherical && ns.gens()[i].owner == m.find_node("B"))
      d[i] = 0.0;
  const NonlinearState s = ns.retract(ns.reference_state(), d);
  // Applied forces: the loads plus arbitrary forces on slave nodes (as if reactions).
  const DofMap& map = ns.reference_map();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map.raw_size());
  for (const auto& l : m.default_case.nodal) {
    f.segment<3>(6 * l.node) += 10.0 * l.force;
    f.segment<3>(6 * l.node + 3) += 10.0 * l.moment;
  }
  f.segment<6>(6 * m.find_node("C")) << 0.4, -0.3, 0.2, 0.1, -0.05, 0.07;
  const auto ev = ns.evaluate(s, f, true);
  const Eigen::MatrixXd K(ev.tangent);
  const double h = 1e-6;
  double worst = 0.0;
  const double scale = K.cwiseAbs().maxCoeff();
  for (int j = 0; j < ns.size(); ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(ns.size());
    e[j] = h;
    const Eigen::VectorXd rp = ns.evaluate(ns.retract(s, e), f, false).residual;
    const Eigen::VectorXd rm = ns.evaluate(ns.retract(s, -e), f, false).residual;
    const Eigen::VectorXd col = (rp - rm) / (2 * h);
    const double err = (col - K.col(j)).cwiseAbs().maxCoeff();
    if (err > 1e-6 * scale) {
      Eigen::Index at;
      (col - K.col(j)).cwiseAbs().maxCoeff(&at);
      ADD_FAILURE() << "column " << j << " kind " << static_cast<int>(ns.gens()[j].kind) << " owner " << ns.gens()[j].owner
                    << " comp " << ns.gens()[j].comp << ": error " << err << " at row " << at << " (kind "
                    << static_cast<int>(ns.gens()[at].kind) << " owner " << ns.gens()[at].owner << " comp " << ns.gens()[at].comp
                    << ") fd " << col[at] << " K " << K(at, j);
    }
    worst = std::max(worst, err);
  }
  EXPECT_LT(worst, 1e-6 * scale) << "scale " << scale;
}

// The curvature term alone matters: without G the check above fails (guards against a G that
// is silently zero). Single rigid link on a hinge, tip force along the link: G = -P L exactly.
TEST(NonlinearStructure, ConstraintCurvatureOfARigidLinkIsMinusPL) {
  const double L = 0.7, P = 3.0;
  json d = rigid_chain(1, L, 5.0);
  const Model m = read_model(d);
  const NonlinearStructure ns(m);
  const NonlinearState s = ns.reference_state();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(ns.reference_map().raw_size());
  f[6 * m.find_node("N1")] = P;  // f_int - f_app at the tip: compression P (applied force -P)
  const SparseMatrix G = ns.constraint_curvature(s, ns.twists(s), f);
  const int q = ns.gen_of_raw(ns.reference_map().raw_joint(0, 0));
  EXPECT_NEAR(G.coeff(q, q), -P * L, 1e-14);
}

// A revolute joint's axis is body-fixed in the body of nodes[0]: rotating that body by R turns
// the spatial axis to R a, and the joint coordinate then spins the child about R a.
TEST(NonlinearStructure, RevoluteAxisTurnsWithItsBody) {
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "A1"}, {"xyz", {0, 0, 0}}},
                            {{"id", "T"}, {"xyz", {1, 0, 0}}}});
  d["elements"] = json::array({{{"id", "r"}, {"type", "rigid"}, {"nodes", {"A1", "T"}}}});
  d["joints"] = json::array({{{"id", "h"}, {"type", "revolute"}, {"nodes", {"A", "A1"}}, {"axes", {{0, 0, 1}}}}});
  d["loads"] = json::array();
  const Model m = read_model(d);
  const NonlinearStructure ns(m);
  Eigen::VectorXd dlt = Eigen::VectorXd::Zero(ns.size());
  const int A = m.find_node("A");
  dlt[ns.gen_of_raw(6 * A + 3)] = M_PI / 2;  // body A turned 90 deg about x: axis z -> -y
  const int q = ns.gen_of_raw(ns.reference_map().raw_joint(0, 0));
  dlt[q] = 0.3;
  const NonlinearState s = ns.retract(ns.reference_state(), dlt);
  const Configuration c = configuration_of(m, s);
  EXPECT_LT((c.joint_axes[0][0] - Vec3(0, -1, 0)).norm(), 1e-12);
  const Mat3 rel = s.R[m.find_node("A1")] * s.R[A].transpose();
  EXPECT_LT((rel - exp_so3(0.3 * Vec3(0, -1, 0))).norm(), 1e-12);
  // The tip: A1's rigid link rotated by R_A exp(0.3 z).
  const Vec3 tip = s.R[A] * exp_so3(0.3 * Vec3::UnitZ()) * Vec3(1, 0, 0);
  EXPECT_LT((s.x[m.find_node("T")] - tip).norm(), 1e-12);
  // The twist of the coordinate is a spin about the current axis through the joint.
  const auto tw = ns.twists(s);
  EXPECT_LT((tw[q].w - Vec3(0, -1, 0)).norm(), 1e-12);
}

// The exact Jacobian of the kinematics equals the linearised constraint map of DofMap built about
// the current Configuration (current offsets, current spatial joint axes) for rigid links and
// rotational joints: both are raw u = T_f u_free at that state.
TEST(NonlinearStructure, JacobianEqualsDofMapAboutTheCurrentConfiguration) {
  json d = jointed_frame();
  // With the virtual spring (translations separate its nodes: DofMap's lever term) and, in a second
  // model, a universal joint in its place.
  for (int variant = 0; variant < 2; ++variant) {
  if (variant == 1)
    d["joints"][2] = {{"id", "j3"}, {"type", "universal"}, {"nodes", {"D", "D1"}}, {"axes", {{0, 0, 1}, {0, 1, 0}}}};
  const Model m = read_model(d);
  const NonlinearStructure ns(m);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd dl(ns.size());
  for (int i = 0; i < ns.size(); ++i) dl[i] = (ns.is_rotation(i) ? 1.0 : 0.05) * U(rng);
  for (int i = 0; i < ns.size(); ++i)
    if (ns.gens()[i].kind != NonlinearStructure::GenKind::JointScalar &&
        ns.gens()[i].kind != NonlinearStructure::GenKind::JointSpherical && ns.gens()[i].owner == m.find_node("B"))
      dl[i] = 0.0;
  const NonlinearState s = ns.retract(ns.reference_state(), dl);
  const DofMap map(m, configuration_of(m, s));
  const auto tw = ns.twists(s);
  double worst = 0.0;
  for (int n = 0; n < static_cast<int>(m.nodes.size()); ++n)
    for (int k = 0; k < 6; ++k) {
      Eigen::VectorXd mine = Eigen::VectorXd::Zero(map.raw_size());
      for (const auto& [g, v] : ns.raw_row(s, tw, n, k)) mine[ns.gens()[g].raw] += v;
      Eigen::VectorXd theirs = Eigen::VectorXd::Zero(map.raw_size());
      for (SparseRowMatrix::InnerIterator it(map.T_free(), map.raw_node(n, k)); it; ++it)
        theirs[map.raw_index(map.free_dofs()[it.col()])] += it.value();
      // Supported DOFs of B are not free in the DofMap: compare on the free ones only.
      for (int f = 0; f < map.free_size(); ++f) {
        const int raw = map.raw_index(map.free_dofs()[f]);
        worst = std::max(worst, std::abs(mine[raw] - theirs[raw]));
      }
    }
  EXPECT_LT(worst, 1e-12) << "variant " << variant;
  }
}

// Failure is an outcome: the end of a rigid link of length L on a hinge spring pushed sideways to
// 1.2 L, beyond its reach. The steps are cut as the link approaches 90 deg, then the path stops with
// the reason, and every converged step (all within reach) is kept.
TEST(NonlinearStructure, PathBeyondReachStopsCleanlyKeepingConvergedSteps) {
  const double L = 0.5;
  const Model m = read_model(rigid_chain(1, L, 20.0));
  PathOptions o;
  o.control = PathControl::Displacement;
  o.control_node = m.find_node("N1");
  o.control_dof = 1;
  o.target = 1.2 * L;
  o.increments = 6;
  o.max_cuts = 8;
  o.track = {m.find_node("N1")};
  const PathResult r = follow_path(m, o);
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.brief_report().find("no convergence"), std::string::npos) << r.brief_report();
  ASSERT_GE(r.steps.size(), 3u);
  for (const auto& st : r.steps) EXPECT_LT(st.track[0][1], L);
  EXPECT_GT(r.steps.back().track[0][1], 0.8 * L);
  // Where y turns back (the link across the x axis) the path goes on under arc length, around the
  // hinge, until y turns back again short of its first turn: the target is out of reach.
  EXPECT_NE(r.brief_report().find("is out of its reach"), std::string::npos) << r.brief_report();
  std::printf("%zu steps: %s\n", r.steps.size() - 1, r.brief_report().c_str());
}

namespace {

// The jointed frame with loops closed through every kind of edge: rigid links from the first body
// to a revolute joint's far side and to the second sub-chain, the virtual spring and the spherical
// joint inside loops. (Which edges close the loops is the forest's choice; the test asserts that
// rigid and joint closures, with translations, are among them.)
json looped_frame() {
  json d = jointed_frame();
  d["nodes"].push_back({{"id", "G"}, {"xyz", {0.6, 0.4, 0.3}}});
  d["nodes"].push_back({{"id", "G1"}, {"xyz", {0.6, 0.4, 0.3}}});
  d["elements"].push_back({{"id", "r3"}, {"type", "rigid"}, {"nodes", {"B1", "G"}}});
  d["elements"].push_back({{"id", "r4"}, {"type", "rigid"}, {"nodes", {"G1", "E"}}});
  d["elements"].push_back({{"id", "r5"}, {"type", "rigid"}, {"nodes", {"C1", "D1"}}});
  d["joints"].push_back({{"id", "j5"}, {"type", "revolute"}, {"nodes", {"G", "G1"}}, {"axes", {{0.0, 0.6, 0.8}}},
                         {"stiffness", {1.5}}});
  // A second loop closed by a virtual spring: both its nodes are reached by rigid links first.
  d["nodes"].push_back({{"id", "H"}, {"xyz", {0.7, -0.2, 0.4}}});
  d["nodes"].push_back({{"id", "H1"}, {"xyz", {0.7, -0.2, 0.4}}});
  d["elements"].push_back({{"id", "r6"}, {"type", "rigid"}, {"nodes", {"C", "H"}}});
  d["elements"].push_back({{"id", "r7"}, {"type", "rigid"}, {"nodes", {"E1", "H1"}}});
  d["joints"].push_back({{"id", "j6"}, {"type", "virtual_spring"}, {"nodes", {"H", "H1"}},
                         {"axes", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"stiffness", {40, 30, 20, 2, 3, 4}}});
  return d;
}

}  // namespace

// Closures of loops (solvers/nonlinear_structure.hpp, "Closed loops"): at a state far from the
// constraint manifold (large rotations everywhere, closures violated), (1) the closure Jacobian is
// the derivative of the closure values, (2) the tangent with the closure curvature contracted with
// arbitrary multipliers is the derivative of the residual T^T (f_int - f_app) + B^T mu, and (3) on the
// manifold (the reference state) the force rows B equal the Jacobian.
TEST(NonlinearStructure, TangentMatchesFiniteDifferenceOfResidualWithLoopClosures) {
  const Model m = read_model(looped_frame());
  const NonlinearStructure ns(m);
  ASSERT_GE(ns.closures().size(), 2u);
  bool rigid = false, joint = false;
  for (const auto& c : ns.closures()) (c.edge.kind == ConstraintEdge::Kind::Rigid ? rigid : joint) = true;
  std::string which;
  for (const auto& c : ns.closures())
    which += (c.edge.kind == ConstraintEdge::Kind::Rigid ? " element " + m.elements[c.edge.index].id
                                                           : " joint " + m.joints[c.edge.index].id);
  EXPECT_TRUE(rigid && joint) << "closures:" << which;
  {
    const NonlinearState s0 = ns.reference_state();
    const auto tw0 = ns.twists(s0);
    EXPECT_LT(ns.closure_values(s0).cwiseAbs().maxCoeff(), 1e-14);
    const Eigen::MatrixXd C0(ns.closure_jacobian(s0, tw0)), B0(ns.closure_force_rows(s0, tw0));
    EXPECT_LT((C0 - B0).cwiseAbs().maxCoeff(), 1e-14);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd d(ns.size());
  for (int i = 0; i < ns.size(); ++i) d[i] = (ns.is_rotation(i) ? 1.1 : 0.05) * U(rng);
  const NonlinearState s = ns.retract(ns.reference_state(), d);
  const auto tw = ns.twists(s);
  Eigen::VectorXd mu(ns.closure_rows());
  for (int i = 0; i < mu.size(); ++i) mu[i] = (i % 6 < 3 ? 2.0 : 0.3) * U(rng);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(ns.reference_map().raw_size());
  for (const auto& l : m.default_case.nodal) f.segment<3>(6 * l.node) += 10.0 * l.force;
  const auto ev = ns.evaluate(s, f, true, mu);
  const Eigen::MatrixXd K(ev.tangent), C(ns.closure_jacobian(s, tw));
  const double h = 1e-6, scale = K.cwiseAbs().maxCoeff();
  double worst_k = 0.0, worst_c = 0.0;
  for (int j = 0; j < ns.size(); ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(ns.size());
    e[j] = h;
    const NonlinearState sp = ns.retract(s, e), sm = ns.retract(s, -e);
    const Eigen::VectorXd col = (ns.evaluate(sp, f, false, mu).residual - ns.evaluate(sm, f, false, mu).residual) / (2 * h);
    worst_k = std::max(worst_k, (col - K.col(j)).cwiseAbs().maxCoeff());
    const Eigen::VectorXd ccol = (ns.closure_values(sp) - ns.closure_values(sm)) / (2 * h);
    worst_c = std::max(worst_c, (ccol - C.col(j)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_k, 1e-6 * scale) << "tangent scale " << scale;
  EXPECT_LT(worst_c, 1e-7) << "closure Jacobian";
  // The closure curvature is not silently zero: without it the tangent misses the FD derivative.
  const Eigen::MatrixXd Gc(ns.closure_curvature(s, tw, mu));
  EXPECT_GT(Gc.cwiseAbs().maxCoeff(), 1e3 * worst_k);
}

}  // namespace nonlinear_tangent_test
