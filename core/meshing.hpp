#pragma once
// Meshing a member into analysis elements (docs/input-format.md, "divisions").
//
// A beam member with "divisions": n becomes n elements of equal length joined by n-1 internal
// nodes named "<member>#1" ... "<member>#(n-1)" on the straight line between its end nodes; the
// elements are "<member>#1" ... "<member>#n" (just "<member>" when n = 1). Work and memory are
// linear in n (ids are looked up through the model's index).
#include <string>

#include "core/model.hpp"

namespace beamfea {

// The id of internal node k (1 <= k < divisions) of a member.
std::string internal_node_id(const std::string& member_id, int k);

// The first internal node id of `member` that is already taken in `model`, or "" if none.
// Call before add_meshed_member, which assumes the ids are free.
std::string taken_internal_node_id(const Model& model, const Member& member);

// Appends `member` (end nodes, type, properties and divisions set; `elements` empty), its
// internal nodes and its elements to `model`; returns the member's index. `spare` (may be null):
// a previous model whose nodes' and elements' storage the new ones take (core/model.hpp, recycled).
int add_meshed_member(Model& model, Member member, Model* spare = nullptr);

}  // namespace beamfea
