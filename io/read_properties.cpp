// Model reader, part 1: nodes, materials, sections (io/model_reader_parts.hpp).
#include <algorithm>
#include <string_view>

#include "core/errors.hpp"
#include "elements/section_shapes.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

void read_nodes(ReadState& s) {
  Model& m = s.model;
  // Optional where the geometry is generated (io/read_generate.cpp).
  const auto& arr = collection(s.doc, "nodes", !s.doc.contains("generate"));
  m.nodes.reserve(arr.size());
  m.node_index.reserve(arr.size());
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/nodes", i);
    const auto& n = object(arr[i], p, "node");
    const Fields f(n, p, {"id", "xyz"});
    Node node = s.item(&Model::nodes, i);
    id_into(node.id, f.require("id", "node"), child(p, "id"), "node");
    // The user's nodes come first: node i is at position i of the model's nodes.
    check_unique(m.find_node(node.id), "node", "/nodes", node.id, i);
    node.x = vec3(f.require("xyz", What("node '", node.id, "'")), child(p, "xyz"), What("node '", node.id, "' xyz"));
    m.add_node(std::move(node));
  }
}

void read_materials(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "materials", false);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/materials", i);
    const auto& o = object(arr[i], p, "material");
    const Fields f(o, p, {"id", "E", "G", "nu", "density", "alpha"});
    Material mat = s.item(&Model::materials, i);
    id_into(mat.id, f.require("id", "material"), child(p, "id"), "material");
    check_unique(m.find_material(mat.id), "material", "/materials", mat.id, i);
    const std::string& what = s.what.assign("material '").append(mat.id).append("'");
    mat.E = positive(f.require("E", what), child(p, "E"), What(what, " E"));
    if (const json* G = f.get("G")) {
      mat.G = positive(*G, child(p, "G"), What(what, " G"));
    } else if (const json* nu_value = f.get("nu")) {
      const double nu = number(*nu_value, child(p, "nu"), What(what, " nu"));
      if (!(nu > -1.0 && nu < 0.5)) throw InputError(child(p, "nu"), what + ": nu must lie in (-1, 0.5)");
      mat.G = mat.E / (2.0 * (1.0 + nu));
    } else {
      throw InputError(child(p, "G"), what + ": missing field 'G' (or 'nu')");
    }
    mat.density = read_density(f.get("density"), p, what);
    if (const json* alpha = f.get("alpha")) {
      mat.alpha = number(*alpha, child(p, "alpha"), What(what, " alpha"));
      if (!(mat.alpha >= 0.0)) throw InputError(child(p, "alpha"), what + ": alpha (thermal expansion) must not be negative");
    }
    m.add_material(std::move(mat));
  }
}

namespace {

// The dimensions of every shape (elements/section_shapes.hpp): the keys of a section besides its
// properties.
constexpr std::string_view kShapeDimensions[] = {"b", "h", "d", "r", "t", "tw", "tf"};

// Reads the section's properties into `sec` (its id already set); `what` holds its name in messages.
void read_section(const Fields& f, const json_in::Pointer& p, Section& sec, const std::string& what) {
  const json* shape_value = f.get("shape");
  if (shape_value) {
    const std::string shape_name = string(*shape_value, child(p, "shape"), what);
    const SectionShape* shape = find_section_shape(shape_name);
    if (!shape)
      throw InputError(child(p, "shape"), what + ": unknown shape '" + shape_name + "' (expected " + section_shape_names() + ")");
    // The shape's dimensions (required, then optional: 0 when absent); a dimension of another
    // shape is an error naming the ones this shape takes.
    ShapeDimensions d{};
    std::size_t n = 0;
    for (const std::string_view key : shape->dimensions) d[n++] = positive(f.require(key, what), child(p, key), What(what, " ", key));
    for (const std::string_view key : shape->optional) {
      const json* v = f.get(key);
      d[n++] = v ? positive(*v, child(p, key), What(what, " ", key)) : 0.0;
    }
    for (const std::string_view key : kShapeDimensions) {
      if (!f.get(key) || std::ranges::count(shape->dimensions, key) || std::ranges::count(shape->optional, key)) continue;
      throw InputError(child(p, key), what + ": shape '" + shape_name + "' takes " + section_shape_dimensions(*shape) + ", not '" +
                                          std::string(key) + "'");
    }
    if (const std::string bad = shape->check(d); !bad.empty()) {
      const std::string key = bad.substr(0, bad.find(':'));
      throw InputError(child(p, key), what + ": " + bad);
    }
    const SectionProperties sp = shape->compute(d);
    sec.A = sp.A;
    sec.Iy = sp.Iy;
    sec.Iz = sp.Iz;
    sec.J = sp.J;
    sec.ky = sp.ky;
    sec.kz = sp.kz;
  }
  // Explicit properties override the shape's.
  auto prop = [&](const char* key, double& out, bool required) {
    if (const json* v = f.get(key)) out = positive(*v, child(p, key), What(what, " ", key));
    else if (required && !shape_value)
      throw InputError(child(p, key), what + ": missing field '" + std::string(key) + "'");
  };
  prop("A", sec.A, true);
  prop("Iy", sec.Iy, true);
  prop("Iz", sec.Iz, true);
  prop("J", sec.J, true);
  if (const json* k = f.get("k")) sec.ky = sec.kz = positive(*k, child(p, "k"), What(what, " k"));
  prop("ky", sec.ky, false);
  prop("kz", sec.kz, false);
}

}  // namespace

void read_sections(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "sections", false);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/sections", i);
    const auto& o = object(arr[i], p, "section");
    const Fields f(o, p, {"id", "shape", "b", "h", "d", "r", "t", "tw", "tf", "A", "Iy", "Iz", "J", "k", "ky", "kz"});
    Section sec = s.item(&Model::sections, i);
    id_into(sec.id, f.require("id", "section"), child(p, "id"), "section");
    check_unique(m.find_section(sec.id), "section", "/sections", sec.id, i);
    read_section(f, p, sec, s.what.assign("section '").append(sec.id).append("'"));
    m.add_section(std::move(sec));
  }
}

}  // namespace beamfea::reader
