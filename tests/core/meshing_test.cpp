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

TEST(ModelIndex, FindsEveryIdOfAThousandAsAScanWouldAndKeepsTheFirstOfTwo) {
  // The open-addressing table grows from 16 slots past several doublings; every id found at its
  // position, a repeated id refused (the first kept), absent ids not found.
  auto id = [](int i) { return std::string("n").append(std::to_string(i)); };
  Model m;
  for (int i = 0; i < 1000; ++i) m.add_node({id(i), Vec3(i, 0, 0), -1});
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(m.find_node(id(i)), i);
  EXPECT_EQ(m.find_node("n1000"), -1);
  EXPECT_EQ(m.find_node(""), -1);
  m.nodes.push_back({"n5", Vec3(9, 9, 9), -1});  // a repeated id pushed directly: the index is out of step
  EXPECT_EQ(m.find_node("n5"), 5);               // a scan finds the first
  EXPECT_EQ(m.node_index.size(), 1000u);
  IdIndex index;
  const std::vector<Node> twice = {{"a", Vec3::Zero(), -1}, {"b", Vec3::Zero(), -1}, {"a", Vec3::Zero(), -1}};
  EXPECT_TRUE(index.add(twice, 0));
  EXPECT_TRUE(index.add(twice, 1));
  EXPECT_FALSE(index.add(twice, 2));
  EXPECT_EQ(index.size(), 2u);
}

TEST(ModelIndex, AClearedModelIndexesItsNextNodesAfresh) {
  Model m = two_nodes();
  m.clear();
  EXPECT_TRUE(m.nodes.empty());
  EXPECT_EQ(m.node_index.size(), 0u);
  EXPECT_EQ(m.find_node("A"), -1);
  m.add_node({"B", Vec3(1, 0, 0), -1});
  m.add_node({"A", Vec3(2, 0, 0), -1});
  EXPECT_EQ(m.find_node("A"), 1);
  EXPECT_EQ(m.find_node("B"), 0);
  // Materials and sections are indexed as nodes are.
  m.add_material({"steel", 2.1e11, 8.1e10, 7850.0});
  m.add_section({"s", 1e-3, 1e-6, 1e-6, 2e-6, 0.0, 0.0});
  EXPECT_EQ(m.find_material("steel"), 0);
  EXPECT_EQ(m.find_section("s"), 0);
  EXPECT_EQ(m.find_section("steel"), -1);
}

TEST(Meshing, AMemberMeshedWithASparesStorageIsTheFreshMembersMesh) {
  // add_meshed_member with a spare model (a reused model's storage): the same nodes and elements
  // as without, whatever the spare held.
  Model spare = two_nodes();
  Member old;
  old.id = "a much longer member id than any here";
  old.nodes = {0, 1};
  old.divisions = 7;
  add_meshed_member(spare, old);
  Model fresh = two_nodes(), reused = two_nodes();
  Member mem;
  mem.id = "e";
  mem.nodes = {0, 1};
  mem.divisions = 3;
  add_meshed_member(fresh, mem);
  add_meshed_member(reused, mem, &spare);  // nodes and elements take the spare's storage
  ASSERT_EQ(reused.nodes.size(), fresh.nodes.size());
  ASSERT_EQ(reused.elements.size(), fresh.elements.size());
  for (std::size_t i = 0; i < fresh.nodes.size(); ++i) {
    EXPECT_EQ(reused.nodes[i].id, fresh.nodes[i].id);
    EXPECT_EQ(reused.nodes[i].x, fresh.nodes[i].x);
    EXPECT_EQ(reused.nodes[i].member, fresh.nodes[i].member);
  }
  for (std::size_t i = 0; i < fresh.elements.size(); ++i) {
    EXPECT_EQ(reused.elements[i].id, fresh.elements[i].id);
    EXPECT_EQ(reused.elements[i].nodes, fresh.elements[i].nodes);
  }
  EXPECT_EQ(reused.members[0].elements, fresh.members[0].elements);
  EXPECT_EQ(reused.find_node("e#2"), fresh.find_node("e#2"));
}

}  // namespace meshing_test
