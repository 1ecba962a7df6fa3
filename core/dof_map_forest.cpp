// DofMap, part 2: the spanning forest of the constraint graph (core/dof_map.hpp, "slave").
#include <algorithm>
#include <array>
#include <vector>

#include "core/dof_map.hpp"

namespace beamfea {

// Spanning forest of the graph of rigid links and joints, rooted at the most supported node of
// each connected component so that supports fall on independent DOFs whenever possible.
// Its arrays are the build scratch's, written over (DofMap::rebuild).
void DofMap::build_forest(const Model& m) {
  BuildScratch& b = scratch_;
  tree_edges_.clear();
  tree_order_.clear();
  loop_edges_.clear();
  build_adjacency(m);
  rank_roots(m);

  parent_edge_.assign(n_nodes_, -1);
  b.visited.assign(n_nodes_, 0);
  b.used_rigid.assign(m.elements.size(), 0);
  b.used_joint.assign(m.joints.size(), 0);
  std::vector<int>& queue = b.queue;
  queue.clear();
  queue.reserve(n_nodes_);
  const std::size_t n_edges = b.adj.size() / 2;
  tree_edges_.reserve(std::min<std::size_t>(n_edges, static_cast<std::size_t>(n_nodes_)));
  tree_order_.reserve(std::min<std::size_t>(n_edges, static_cast<std::size_t>(n_nodes_)));
  // Grounds: nodes whose six DOFs are all supported or prescribed. Every ground is a root, and one
  // breadth-first search from all grounds at once carries each node from its nearest ground: chains
  // stay short, and a loop between two grounds closes at an edge in its middle (a closure) rather
  // than through the supports of a slave (which would make one long chain through the loop). Then the
  // remaining components, each from its most supported node.
  auto has_edges = [&](int n) { return b.first[n + 1] > b.first[n]; };
  for (int n : b.order)
    if (has_edges(n) && std::all_of(b.held[n].begin(), b.held[n].end(), [](char h) { return h != 0; })) {
      b.visited[n] = 1;
      queue.push_back(n);
    }
  search_forest(m);
  for (int root : b.order) {
    if (b.visited[root] || !has_edges(root)) continue;
    b.visited[root] = 1;
    queue.assign(1, root);
    search_forest(m);
  }
}

// Adjacency lists in one array (node n's are adj[first[n]] .. adj[first[n + 1] - 1]), each in the
// order rigid links by element, then joints by joint.
void DofMap::build_adjacency(const Model& m) {
  using Adj = BuildScratch::Adj;
  BuildScratch& b = scratch_;
  std::vector<int>& first = b.first;
  first.assign(n_nodes_ + 1, 0);
  auto for_each_edge = [&](auto&& f) {
    for (int e = 0; e < static_cast<int>(m.elements.size()); ++e) {
      const auto& el = m.elements[e];
      if (el.type != MemberType::Rigid) continue;
      f(el.nodes[0], Adj{ConstraintEdge::Kind::Rigid, e, el.nodes[1]});
      f(el.nodes[1], Adj{ConstraintEdge::Kind::Rigid, e, el.nodes[0]});
    }
    for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
      const auto& jt = m.joints[j];
      f(jt.nodes[0], Adj{ConstraintEdge::Kind::Joint, j, jt.nodes[1]});
      f(jt.nodes[1], Adj{ConstraintEdge::Kind::Joint, j, jt.nodes[0]});
    }
  };
  for_each_edge([&](int n, const Adj&) { ++first[n + 1]; });
  for (int n = 0; n < n_nodes_; ++n) first[n + 1] += first[n];
  std::vector<Adj>& adj = b.adj;
  adj.resize(first[n_nodes_]);
  std::vector<int>& fill = b.fill;
  fill.assign(first.begin(), first.end() - 1);
  for_each_edge([&](int n, const Adj& a) { adj[fill[n]++] = a; });
}

// Per node, the components held (supported or prescribed) and their count; the nodes ordered most
// supported first, ties in node order.
void DofMap::rank_roots(const Model& m) {
  BuildScratch& b = scratch_;
  std::vector<int>& support_count = b.support_count;
  support_count.assign(n_nodes_, 0);
  for (const auto& s : m.supports)
    for (bool f : s.fixed) support_count[s.node] += f ? 1 : 0;
  for (const auto& p : m.prescribed)
    if (p.dof.owner == DofRef::Owner::Node) support_count[p.dof.index] += 1;
  std::vector<std::array<char, 6>>& held = b.held;
  held.assign(n_nodes_, std::array<char, 6>{});
  for (const auto& s : m.supports)
    for (int k = 0; k < 6; ++k) held[s.node][k] = held[s.node][k] || s.fixed[k];
  for (const auto& p : m.prescribed)
    if (p.dof.owner == DofRef::Owner::Node) held[p.dof.index][p.dof.comp] = 1;
  // The order of a stable sort by support count, by a sort that needs no buffer (std::stable_sort
  // allocates one on every call).
  std::vector<int>& order = b.order;
  order.resize(n_nodes_);
  for (int i = 0; i < n_nodes_; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return support_count[x] != support_count[y] ? support_count[x] > support_count[y] : x < y;
  });
}

// Breadth first from the nodes in the scratch's queue (a FIFO: `head` is its front): an edge to an
// unvisited node joins the forest, an edge to a visited one closes a loop.
void DofMap::search_forest(const Model& m) {
  using Adj = BuildScratch::Adj;
  BuildScratch& b = scratch_;
  std::vector<int>& queue = b.queue;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int n = queue[head];
    for (int ai = b.first[n]; ai < b.first[n + 1]; ++ai) {
      const Adj& a = b.adj[ai];
      auto& used = a.kind == ConstraintEdge::Kind::Rigid ? b.used_rigid[a.index] : b.used_joint[a.index];
      if (used) continue;
      used = 1;
      ConstraintEdge e;
      e.kind = a.kind;
      e.index = a.index;
      if (!b.visited[a.other]) {
        b.visited[a.other] = 1;
        e.parent = n;
        e.child = a.other;
        e.forward = a.kind == ConstraintEdge::Kind::Joint ? m.joints[a.index].nodes[0] == n : true;
        parent_edge_[a.other] = static_cast<int>(tree_edges_.size());
        tree_order_.push_back(static_cast<int>(tree_edges_.size()));
        tree_edges_.push_back(e);
        queue.push_back(a.other);
      } else {
        // Closes a loop: kept as an extra constraint, written from nodes[0] to nodes[1].
        const auto& ends = a.kind == ConstraintEdge::Kind::Rigid ? m.elements[a.index].nodes : m.joints[a.index].nodes;
        e.parent = ends[0];
        e.child = ends[1];
        e.forward = true;
        loop_edges_.push_back(e);
      }
    }
  }
}

}  // namespace beamfea
