// Tension-only and compression-only members (solvers/second_order.hpp): a slack member leaves the
// structure, so the answer is that of the same structure without it.
#include <gtest/gtest.h>

#include <cmath>

#include "nl_models.hpp"
#include "solvers/second_order.hpp"

namespace tension_only_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
const double E = 210e9, G = 81e9;

// A portal frame in the x-y plane: columns A-C and B-D (4 m apart, 3 m high, clamped at A and B),
// beam C-D, and the X-bracing AD and BC (rods of small bending stiffness) with `behaviour`
// ("" for none); `drop` names a diagonal left out ("" for none). The lateral load H (+x) at C, gravity loads
// V at C and D.
json braced_frame(const std::string& behaviour, const std::string& drop, int diagonal_divisions, double H, double V) {
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {4, 0, 0}}},
                            {{"id", "C"}, {"xyz", {0, 3, 0}}}, {{"id", "D"}, {"xyz", {4, 3, 0}}}});
  d["materials"] = json::array({{{"id", "steel"}, {"E", E}, {"G", G}}});
  d["sections"] = json::array({{{"id", "col"}, {"A", 5e-3}, {"Iy", 2e-5}, {"Iz", 4e-5}, {"J", 1e-6}},
                               {{"id", "rod"}, {"A", 3e-4}, {"Iy", 1e-9}, {"Iz", 1e-9}, {"J", 2e-9}}});
  const auto beam = [](const char* id, const char* a, const char* b, const char* section) {
    return json{{"id", id}, {"type", "beam"}, {"nodes", {a, b}}, {"material", "steel"}, {"section", section},
                {"orientation", {0, 0, 1}}};
  };
  d["elements"] = json::array({beam("AC", "A", "C", "col"), beam("BD", "B", "D", "col"), beam("CD", "C", "D", "col")});
  json ad = beam("AD", "A", "D", "rod"), bc = beam("BC", "B", "C", "rod");
  for (json* diagonal : {&ad, &bc}) {
    if (!behaviour.empty()) (*diagonal)["behaviour"] = behaviour;
    (*diagonal)["divisions"] = diagonal_divisions;
  }
  if (drop != "AD") d["elements"].push_back(ad);
  if (drop != "BC") d["elements"].push_back(bc);
  d["supports"] = json::array({fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}), fix("B", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array({load("C", H, -V, 0), load("D", 0, -V, 0)});
  return d;
}

SecondOrderResult solve(const json& d, bool geometric) {
  const Model m = read_model(d);
  SecondOrderOptions o;
  o.geometric = geometric;
  return solve_second_order(m, m.default_loads(), o);
}

void expect_same_nodes(const SecondOrderResult& a, const SecondOrderResult& b) {
  // Nodes A..D come first in both models (the meshed diagonals' interior nodes after them).
  const Eigen::VectorXd ua = a.solution.u.head(24), ub = b.solution.u.head(24);
  EXPECT_LE((ua - ub).cwiseAbs().maxCoeff(), 1e-10 * ub.cwiseAbs().maxCoeff());
  for (int n = 0; n < 2; ++n)
    EXPECT_LE((a.solution.reactions[n] - b.solution.reactions[n]).cwiseAbs().maxCoeff(),
              1e-8 * b.solution.reactions[n].cwiseAbs().maxCoeff());
}
}  // namespace

// Sway to +x stretches AD and shortens BC: the tension-only BC goes slack, and the frame answers as
// the frame without BC, in linear statics and in second order, meshed diagonals or not.
TEST(TensionOnly, BracedFrameWithASlackDiagonalEqualsTheFrameWithoutIt) {
  for (bool geometric : {false, true})
    for (int divisions : {1, 4}) {
      const SecondOrderResult r = solve(braced_frame("tension_only", "", divisions, 1e4, 1e5), geometric);
      ASSERT_EQ(r.status, SecondOrderStatus::Converged) << r.message;
      const Model m = read_model(braced_frame("tension_only", "", divisions, 1e4, 1e5));
      ASSERT_EQ(r.inactive_members.size(), 1u);
      EXPECT_EQ(m.members[r.inactive_members[0]].id, "BC");
      const SecondOrderResult without = solve(braced_frame("", "BC", divisions, 1e4, 1e5), geometric);
      ASSERT_EQ(without.status, SecondOrderStatus::Converged) << without.message;
      expect_same_nodes(r, without);
      // The slack member carries nothing.
      for (const int e : m.members[r.inactive_members[0]].elements) EXPECT_EQ(r.solution.end_forces[e].norm(), 0.0);
      // With both diagonals carrying either sign the frame is stiffer: BC mattered.
      const SecondOrderResult both = solve(braced_frame("", "", divisions, 1e4, 1e5), geometric);
      EXPECT_GT((both.solution.u.head(24) - r.solution.u.head(24)).norm(), 1e-2 * r.solution.u.head(24).norm());
      // The linear step is the linear statics' answer, slack member settled.
      if (!geometric) {
        EXPECT_EQ(r.linear.u, r.solution.u);
      }
    }
}

// Compression-only diagonals: the stretched AD goes slack instead, and the frame answers as the
// frame without AD.
TEST(TensionOnly, CompressionOnlyDiagonalThatIsStretchedGoesSlack) {
  const SecondOrderResult r = solve(braced_frame("compression_only", "", 1, 1e4, 0.0), false);
  ASSERT_EQ(r.status, SecondOrderStatus::Converged) << r.message;
  const Model m = read_model(braced_frame("compression_only", "", 1, 1e4, 0.0));
  ASSERT_EQ(r.inactive_members.size(), 1u);
  EXPECT_EQ(m.members[r.inactive_members[0]].id, "AD");
  expect_same_nodes(r, solve(braced_frame("", "AD", 1, 1e4, 0.0), false));
}

// A node held by a tension-only rod alone, pushed towards the support: the rod goes slack and the
// node is free, a mechanism that names the slack member.
TEST(TensionOnly, SlackMemberThatLeavesAMechanismIsNamed) {
  json d = straight_member(2.0, 1, E, G, 1e-4, 1e-8, 1e-8, 2e-8);
  d["elements"][0]["behaviour"] = "tension_only";
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -100.0, 0, 0));
  const SecondOrderResult r = solve(d, false);
  ASSERT_EQ(r.status, SecondOrderStatus::Mechanism) << r.message;
  EXPECT_NE(r.message.find("slack members 'bar'"), std::string::npos) << r.message;
  // Pulled instead, it carries the load: N = P.
  d["loads"][0] = load("B", 100.0, 0, 0);
  const SecondOrderResult t = solve(d, false);
  ASSERT_EQ(t.status, SecondOrderStatus::Converged) << t.message;
  EXPECT_TRUE(t.inactive_members.empty());
  EXPECT_NEAR(t.solution.end_forces[0][6], 100.0, 1e-9);
}

}  // namespace tension_only_test
