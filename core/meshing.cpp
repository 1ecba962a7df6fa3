#include "core/meshing.hpp"

namespace beamfea {

std::string internal_node_id(const std::string& member_id, int k) { return member_id + "#" + std::to_string(k); }

std::string taken_internal_node_id(const Model& model, const Member& member) {
  for (int k = 1; k < member.divisions; ++k) {
    std::string id = internal_node_id(member.id, k);
    if (model.find_node(id) >= 0) return id;
  }
  return "";
}

int add_meshed_member(Model& model, Member mem) {
  const int mi = static_cast<int>(model.members.size());
  const Vec3 x1 = model.nodes[mem.nodes[0]].x, x2 = model.nodes[mem.nodes[1]].x;
  const int n = mem.divisions;
  mem.elements.clear();
  mem.elements.reserve(n);
  int prev = mem.nodes[0];
  for (int k = 0; k < n; ++k) {
    int next = mem.nodes[1];
    if (k + 1 < n) {
      Node node;
      node.id = internal_node_id(mem.id, k + 1);
      node.x = x1 + (x2 - x1) * (static_cast<double>(k + 1) / n);
      node.member = mi;
      next = model.add_node(std::move(node));
    }
    Element e;
    e.id = n == 1 ? mem.id : internal_node_id(mem.id, k + 1);
    e.type = mem.type;
    e.nodes = {prev, next};
    e.material = mem.material;
    e.section = mem.section;
    e.orientation = mem.orientation;
    e.theory = mem.theory;
    e.member = mi;
    mem.elements.push_back(static_cast<int>(model.elements.size()));
    model.elements.push_back(std::move(e));
    prev = next;
  }
  return model.add_member(std::move(mem));
}

}  // namespace beamfea
