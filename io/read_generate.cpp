// Model reader, part 7: "generate", geometry the reader makes instead of listing it
// (docs/input-format.md, "Generated geometry"):
//   "generate": {"lattice": {"cells": [nx, ny, nz], "pitch": p | [px, py, pz], "section": id,
//                            "material": id, "origin": [x, y, z], "prefix": ""}}
// A cubic lattice frame of nx x ny x nz cells: (nx+1)(ny+1)(nz+1) nodes "<prefix><i>_<j>_<k>" at
// origin + (i px, j py, k pz), and a beam member on every cell edge, one element each, Euler-Bernoulli,
// default orientation: "<prefix>x<i>_<j>_<k>" from node (i,j,k) to (i+1,j,k), "<prefix>y<i>_<j>_<k>"
// to (i,j+1,k), "<prefix>z<i>_<j>_<k>" to (i,j,k+1). Read after the elements (the listed nodes and
// members keep their positions, /nodes/<i> and /elements/<i>) and before the supports and loads,
// which can name the generated nodes.
#include <fmt/format.h>

#include <array>
#include <cstdint>

#include "core/errors.hpp"
#include "core/meshing.hpp"
#include "io/json_util.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

namespace {

// At most this many generated nodes (about 1.5 kB of model per node with its three members: 1.5 GB;
// 6e6 DOFs), so that a typing slip cannot exhaust the memory.
constexpr std::int64_t kMaxLatticeNodes = 1'000'000;

std::array<int, 3> read_cells(const json& v, const Pointer& p) {
  if (!v.is_array() || v.size() != 3) throw InputError(p, "generate lattice cells: expected [nx, ny, nz]");
  std::array<int, 3> n{};
  std::int64_t nodes = 1;
  for (int d = 0; d < 3; ++d) {
    n[d] = integer_in(v[d], child(p, d), "generate lattice cells", 1, static_cast<int>(kMaxLatticeNodes));
    nodes *= n[d] + 1;
    if (nodes > kMaxLatticeNodes)
      throw InputError(p, fmt::format("generate lattice: (nx+1)(ny+1)(nz+1) nodes exceed the limit of {}", kMaxLatticeNodes));
  }
  return n;
}

Vec3 read_pitch(const json& v, const Pointer& p) {
  if (v.is_array()) {
    const Vec3 pitch = vec3(v, p, "generate lattice pitch");
    for (int d = 0; d < 3; ++d)
      if (!(pitch[d] > 0.0)) throw InputError(child(p, d), "generate lattice pitch must be positive");
    return pitch;
  }
  const double h = positive(v, p, "generate lattice pitch");
  return Vec3(h, h, h);
}

}  // namespace

void read_generate(ReadState& s) {
  const json* g = field(s.doc, "generate");
  if (!g) return;
  const Pointer p("/generate");
  const Fields fg(object(*g, p, "generate"), p, {"lattice"});
  const json* lattice = fg.get("lattice");
  if (!lattice) return;
  const Pointer lp = child(p, "lattice");
  const Fields f(object(*lattice, lp, "generate lattice"), lp, {"cells", "pitch", "section", "material", "origin", "prefix"});
  Model& m = s.model;
  const std::array<int, 3> n = read_cells(f.require("cells", "generate lattice"), child(lp, "cells"));
  const Vec3 pitch = read_pitch(f.require("pitch", "generate lattice"), child(lp, "pitch"));
  const std::string mid = id(f.require("material", "generate lattice"), child(lp, "material"), "generate lattice material");
  const int material = m.find_material(mid);
  if (material < 0) throw InputError(child(lp, "material"), "generate lattice: unknown material '" + mid + "'");
  const std::string sid = id(f.require("section", "generate lattice"), child(lp, "section"), "generate lattice section");
  const int section = m.find_section(sid);
  if (section < 0) throw InputError(child(lp, "section"), "generate lattice: unknown section '" + sid + "'");
  Vec3 origin = Vec3::Zero();
  if (const json* o = f.get("origin")) origin = vec3(*o, child(lp, "origin"), "generate lattice origin");
  std::string prefix;
  if (const json* pr = f.get("prefix")) prefix = string(*pr, child(lp, "prefix"), "generate lattice prefix");

  const auto nx = n[0] + 1, ny = n[1] + 1, nz = n[2] + 1;
  const std::size_t count = static_cast<std::size_t>(nx) * ny * nz;
  const int first = static_cast<int>(m.nodes.size());
  const auto at = [&](int i, int j, int k) { return first + i + nx * (j + ny * k); };
  m.nodes.reserve(m.nodes.size() + count);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        Node node;
        node.id = fmt::format("{}{}_{}_{}", prefix, i, j, k);
        if (m.find_node(node.id) >= 0)
          throw InputError(child(lp, "prefix"), "generate lattice: node id '" + node.id + "' is taken (give another \"prefix\")");
        node.x = origin + Vec3(i * pitch.x(), j * pitch.y(), k * pitch.z());
        m.add_node(std::move(node));
      }
  const std::size_t edges = static_cast<std::size_t>(n[0]) * ny * nz + static_cast<std::size_t>(nx) * n[1] * nz +
                            static_cast<std::size_t>(nx) * ny * n[2];
  m.members.reserve(m.members.size() + edges);
  m.elements.reserve(m.elements.size() + edges);
  const char axis_name[3] = {'x', 'y', 'z'};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int d = 0; d < 3; ++d) {
          const std::array<int, 3> to{i + (d == 0), j + (d == 1), k + (d == 2)};
          if (to[0] >= nx || to[1] >= ny || to[2] >= nz) continue;
          Member mem;
          mem.id = fmt::format("{}{}{}_{}_{}", prefix, axis_name[d], i, j, k);
          if (m.find_member(mem.id) >= 0)
            throw InputError(child(lp, "prefix"), "generate lattice: element id '" + mem.id + "' is taken (give another \"prefix\")");
          mem.type = MemberType::Beam;
          mem.nodes = {at(i, j, k), at(to[0], to[1], to[2])};
          mem.material = material;
          mem.section = section;
          // Default orientation as for a listed beam: global Z in the local x-z plane; global X for a vertical one.
          mem.orientation = d == 2 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
          add_meshed_member(m, std::move(mem));
        }
}

}  // namespace beamfea::reader
