// Meshing a member into elements (core/meshing.hpp) and the model's id index.
#include <gtest/gtest.h>

#include "core/meshing.hpp"

namespace meshing_test {

using namespace beamfea;

namespace {

Model two_nodes() {
  Model m;
  m.add_node({"A", Vec3(0, 0, 0), -1});
  m.add_node({"B", Vec3(4, 0, 2), -1});
  return m;
}

}  // namespace

TEST(Meshing, DividesAMemberIntoEqualElementsWithNamedInternalNodes) {
  Model m = two_nodes();
  Member mem;
  mem.id = "e";
  mem.nodes = {0, 1};
  mem.divisions = 4;
  const int mi = add_meshed_member(m, mem);
  ASSERT_EQ(m.nodes.size(), 5u);
  ASSERT_EQ(m.elements.size(), 4u);
  EXPECT_EQ(m.members[mi].elements, (std::vector<int>{0, 1, 2, 3}));
  for (int k = 1; k < 4; ++k) {
    const int n = m.find_node("e#" + std::to_string(k));
    ASSERT_GE(n, 0);
    // Equal division of the chord A-B: x = A + k/4 (B - A).
    EXPECT_LT((m.nodes[n].x - Vec3(k, 0, 0.5 * k)).norm(), 1e-15);
    EXPECT_EQ(m.nodes[n].member, mi);
  }
  EXPECT_EQ(m.elements[0].nodes[0], 0);
  EXPECT_EQ(m.elements[3].nodes[1], 1);
  EXPECT_EQ(m.elements[3].id, "e#4");
  EXPECT_EQ(m.find_member("e"), mi);
}

TEST(Meshing, TakenInternalNodeIdIsReported) {
  Model m = two_nodes();
  m.add_node({"e#2", Vec3(1, 1, 1), -1});
  Member mem;
  mem.id = "e";
  mem.nodes = {0, 1};
  mem.divisions = 3;
  EXPECT_EQ(taken_internal_node_id(m, mem), "e#2");
  mem.divisions = 2;
  EXPECT_EQ(taken_internal_node_id(m, mem), "");
}

TEST(ModelIndex, LookupsStayRightWhenNodesArePushedDirectly) {
  Model m = two_nodes();
  m.nodes.push_back({"C", Vec3(1, 0, 0), -1});  // bypasses the index: lookups scan
  EXPECT_EQ(m.find_node("C"), 2);
  EXPECT_EQ(m.find_node("A"), 0);
  m.add_node({"D", Vec3(2, 0, 0), -1});  // rebuilds the index
  EXPECT_EQ(m.find_node("C"), 2);
  EXPECT_EQ(m.find_node("D"), 3);
  EXPECT_EQ(m.find_node("nope"), -1);
}

}  // namespace meshing_test
