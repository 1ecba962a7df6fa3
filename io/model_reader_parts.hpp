#pragma once
// The model reader's parts, one per collection of the model file (io/model_reader.cpp calls them
// in order; each appends to the model and throws InputError naming the JSON pointer):
//   io/read_properties.cpp  nodes, materials, sections
//   io/read_members.cpp     elements (members), meshed by core/meshing
//   io/read_joints.cpp      joints
//   io/read_pose.cpp        the pose (read last: it names joints and nodes)
//   io/read_boundary.cpp    supports, loads (io/load_reader.cpp: nodal, joint and member loads,
//                           gravity, masses, load cases, combinations), prescribed values, ties,
//                           linear constraints
//   io/read_damping.cpp     the top-level damping of the dynamic analyses
//   io/read_solver.cpp      the top-level linear solver choice
//   io/read_generate.cpp    generated geometry (a lattice frame's nodes and members)
// Internal to io/: not installed as an API.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "io/json_pointer.hpp"

namespace beamfea::reader {

using json = nlohmann::json;

// What the parts share while reading one document.
struct ReadState {
  const json& doc;
  Model& model;
  Model* spare = nullptr;     // a previous model whose storage the items read take (may be null:
                              // core/model.hpp, recycled)
  double length_scale = 1.0;  // of the user's nodes, computed once
  // The item being read, as messages name it ("material 'steel'"): one string written over item
  // after item (a ModelBuffer's, kept from read to read: no allocation per item or per read).
  std::string& what;
  // A default item for position i of the model's collection, with the spare's storage.
  template <class T>
  T item(std::vector<T> Model::*collection, std::size_t i) const {
    return recycled(spare ? &(spare->*collection) : nullptr, i);
  }
};

// A beam theory by name ("euler_bernoulli", "timoshenko"); InputError at `pointer` otherwise.
BeamTheory beam_theory(const std::string& name, const json_in::Pointer& pointer, const std::string& what);

// The array at doc[key] (pointer "/key"); an empty array when absent and not required.
const json& collection(const json& doc, const char* key, bool required);

// Item `i` of the collection at `base` has id `id`, already held by item `first` (-1: by none, the
// id index of the model or of the reader answers): a repeated id is an InputError naming both places.
void check_unique(int first, const std::string& kind, const json_in::Pointer& base, const std::string& id, std::size_t i);

// A node DOF {"node", "dof"} or a joint coordinate {"joint", "coordinate"} named in object `e`.
DofRef read_dof_target(const Model& m, const json& e, const json_in::Pointer& p, const std::string& what);

void read_nodes(ReadState& s);
void read_materials(ReadState& s);
void read_sections(ReadState& s);
void read_members(ReadState& s);
void read_joints(ReadState& s);
void read_supports(ReadState& s);
void read_loads(ReadState& s);
void read_prescribed(ReadState& s);
void read_ties(ReadState& s);
// "pose": into Model::pose (io/read_pose.cpp); the model is moved to it afterwards.
void read_pose(ReadState& s);
void read_constraints(ReadState& s);
void read_damping(ReadState& s);
void read_solver(ReadState& s);
// "generate": nodes and members of generated geometry (io/read_generate.cpp), after the elements.
void read_generate(ReadState& s);

}  // namespace beamfea::reader
