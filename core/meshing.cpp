#include "core/meshing.hpp"

#include <charconv>

namespace beamfea {

namespace {
// internal_node_id written over `out` (its storage reused).
void assign_internal_node_id(std::string& out, const std::string& member_id, int k) {
  char digits[16];
  const auto end = std::to_chars(digits, digits + sizeof digits, k).ptr;
  out.assign(member_id).append(1, '#').append(digits, end);
}
}  // namespace

std::string internal_node_id(const std::string& member_id, int k) {
  std::string id;
  assign_internal_node_id(id, member_id, k);
  return id;
}

std::string taken_internal_node_id(const Model& model, const Member& member) {
  std::string id;
  for (int k = 1; k < member.divisions; ++k) {
    assign_internal_node_id(id, member.id, k);
    if (model.find_node(id) >= 0) return id;
  }
  return "";
}

int add_meshed_member(Model& model, Member mem, Model* spare) {
  const int mi = static_cast<int>(model.members.size());
  // The flexible part runs from F1 to F2: the ends moved by the offsets, then shortened by the
  // rigid end zones along the line between them (the reader checks that something is left).
  const Vec3 X1 = model.nodes[mem.nodes[0]].x, X2 = model.nodes[mem.nodes[1]].x;
  const Vec3 P1 = X1 + mem.offsets[0], P2 = X2 + mem.offsets[1];
  const Vec3 axis = (P2 - P1).normalized();
  const Vec3 x1 = P1 + mem.rigid_ends[0] * axis, x2 = P2 - mem.rigid_ends[1] * axis;
  const int n = mem.divisions;
  mem.elements.clear();
  mem.elements.reserve(n);
  int prev = mem.nodes[0];
  for (int k = 0; k < n; ++k) {
    int next = mem.nodes[1];
    if (k + 1 < n) {
      Node node = recycled(spare ? &spare->nodes : nullptr, model.nodes.size());
      assign_internal_node_id(node.id, mem.id, k + 1);
      node.x = x1 + (x2 - x1) * (static_cast<double>(k + 1) / n);
      node.member = mi;
      next = model.add_node(std::move(node));
    }
    Element e = recycled(spare ? &spare->elements : nullptr, model.elements.size());
    if (n == 1) e.id = mem.id;
    else assign_internal_node_id(e.id, mem.id, k + 1);
    e.type = mem.type;
    e.nodes = {prev, next};
    e.material = mem.material;
    e.section = mem.section;
    e.orientation = mem.orientation;
    e.theory = mem.theory;
    e.member = mi;
    e.released = {};
    for (int c = 0; c < 6; ++c) {
      if (k == 0) e.released[c] = mem.releases[0][c];
      if (k + 1 == n) e.released[6 + c] = mem.releases[1][c];
    }
    e.offsets = {k == 0 ? Vec3(x1 - X1) : Vec3::Zero(), k + 1 == n ? Vec3(x2 - X2) : Vec3::Zero()};
    mem.elements.push_back(static_cast<int>(model.elements.size()));
    model.elements.push_back(std::move(e));
    prev = next;
  }
  return model.add_member(std::move(mem));
}

}  // namespace beamfea
