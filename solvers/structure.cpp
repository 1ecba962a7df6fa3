#include "solvers/structure.hpp"

#include <array>
#include <span>
#include <type_traits>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"
#include "solvers/element_factory.hpp"
#include "solvers/member_loading.hpp"

namespace beamfea {

BeamSection beam_section(const Model& m, const Element& e) {
  const auto& mat = m.materials.at(e.material);
  const auto& sec = m.sections.at(e.section);
  BeamSection s{mat.E, mat.G, sec.A, sec.Iy, sec.Iz, sec.J};
  if (e.theory == BeamTheory::Timoshenko) {
    if (!(sec.ky > 0.0 && sec.kz > 0.0))
      throw ModelError("element '" + e.id + "'", "a Timoshenko beam needs the shear factors ky, kz of section '" + sec.id + "'");
    s.Asy = sec.A / sec.ky;
    s.Asz = sec.A / sec.kz;
  }
  return s;
}

void LinearStructure::rebuild(const Model& model) {
  model_ = &model;
  // 3.5 KB per element (37 MB at 21,504 DOFs): huge pages before the first touch (core/huge_pages.hpp),
  // so only when the storage is new; a rebuild of a model that fits writes over the last one's.
  if (beams_.capacity() < model.elements.size()) {
    beams_.clear();
    beams_.reserve(model.elements.size());
    advise_huge_pages(beams_.data(), beams_.capacity() * sizeof(beams_[0]));
  }
  beams_.assign(model.elements.size(), std::nullopt);
  transformed_.clear();
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& el = model.elements[e];
    if (el.type != MemberType::Beam) continue;
    if (is_transformed(el)) {
      transformed_.resize(model.elements.size());
      transformed_[e] = make_frame_element(model, static_cast<int>(e), Kinematics::Linear);
      continue;
    }
    try {
      beams_[e].emplace(beam_section(model, el), model.nodes[el.nodes[0]].x, model.nodes[el.nodes[1]].x,
                        el.orientation);
    } catch (const Error& err) {  // the element's own error, named here
      throw ModelError("element '" + el.id + "'", err.what());
    }
  }
}

std::array<int, 12> LinearStructure::element_dofs(const DofMap& map, int element) const {
  const auto& el = model_->elements[element];
  std::array<int, 12> d{};
  for (int k = 0; k < 6; ++k) {
    d[k] = map.raw_node(el.nodes[0], k);
    d[6 + k] = map.raw_node(el.nodes[1], k);
  }
  return d;
}

AssemblyBlocks LinearStructure::assembly_blocks(const Model& model, const DofMap& map) {
  AssemblyBlocks blocks;
  blocks.start.reserve(model.elements.size() + model.joints.size() + 1);
  blocks.raw.reserve(12 * model.elements.size());
  // As assemble_into: the beams in element order (rebuild makes one for each beam element), then
  // the joints with stiffness.
  std::array<int, 12> d{};
  for (const auto& el : model.elements) {
    if (el.type != MemberType::Beam) continue;
    for (int k = 0; k < 6; ++k) {
      d[k] = map.raw_node(el.nodes[0], k);
      d[6 + k] = map.raw_node(el.nodes[1], k);
    }
    blocks.add(d);
  }
  std::vector<int> many;
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const auto& jt = model.joints[j];
    if (!jt.has_stiffness()) continue;
    many.resize(static_cast<std::size_t>(jt.coordinates()));
    for (int q = 0; q < jt.coordinates(); ++q) many[q] = map.raw_joint(static_cast<int>(j), q);
    blocks.add(many);
  }
  return blocks;
}

std::size_t LinearStructure::assembly_entries() const {
  std::size_t entries = 0;  // 12 x 12 per beam, nq x nq per joint with stiffness
  for (std::size_t e = 0; e < beams_.size(); ++e) entries += beam(static_cast<int>(e)) ? 144 : 0;
  for (const auto& jt : model_->joints)
    if (jt.has_stiffness()) entries += static_cast<std::size_t>(jt.coordinates()) * jt.coordinates();
  return entries;
}

template <class Assembler>
void LinearStructure::assemble_into(const DofMap& map, Assembler& assembler) const {
  // The first pass collects triplets: room for them all at once. A later pass writes through the
  // pattern.
  if constexpr (std::is_same_v<Assembler, SystemAssembler>)
    if (!assembler.has_pattern()) assembler.expect(assembly_entries());
  for (std::size_t e = 0; e < beams_.size(); ++e) {
    const FrameElement* b = beam(static_cast<int>(e));
    if (!b) continue;
    const auto dofs = element_dofs(map, static_cast<int>(e));
    // One process's share of a distributed solve: the matrices of the elements it needs, only.
    if constexpr (std::is_same_v<Assembler, SystemAssembler>)
      if (!assembler.reaches_owned(dofs)) continue;
    assembler.add(dofs, b->stiffness());
  }
  // A joint has at most 6 coordinates: its stiffness and DOF list stay on the stack.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> Kj;
  std::array<int, 6> dofs{};
  for (std::size_t j = 0; j < model_->joints.size(); ++j) {
    const auto& jt = model_->joints[j];
    if (!jt.has_stiffness()) continue;
    const int nq = jt.coordinates();
    if (nq > 6) {  // not a joint the reader makes; kept general
      std::vector<int> many(nq);
      for (int q = 0; q < nq; ++q) many[q] = map.raw_joint(static_cast<int>(j), q);
      assembler.add(many, jt.stiffness_as_matrix());
      continue;
    }
    if (jt.stiffness_matrix.size() > 0) {
      Kj = jt.stiffness_matrix;
    } else {
      Kj.setZero(nq, nq);
      for (int i = 0; i < nq && i < static_cast<int>(jt.stiffness.size()); ++i) Kj(i, i) = jt.stiffness[i];
    }
    for (int q = 0; q < nq; ++q) dofs[q] = map.raw_joint(static_cast<int>(j), q);
    assembler.add(std::span<const int>(dofs.data(), nq), Kj);
  }
}

void LinearStructure::assemble(const DofMap& map, SystemAssembler& assembler) const { assemble_into(map, assembler); }
void LinearStructure::assemble(const DofMap& map, DenseAssembler& assembler) const { assemble_into(map, assembler); }

Eigen::VectorXd LinearStructure::internal_force(const DofMap& map, const Eigen::VectorXd& u) const {
  Eigen::VectorXd f;
  internal_force(map, u, f);
  return f;
}

void LinearStructure::internal_force(const DofMap& map, const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  f.setZero(map.raw_size());
  for (std::size_t e = 0; e < beams_.size(); ++e) {
    const FrameElement* b = beam(static_cast<int>(e));
    if (!b) continue;
    const auto dofs = element_dofs(map, static_cast<int>(e));
    Vec12 ue;
    for (int k = 0; k < 12; ++k) ue[k] = u[dofs[k]];
    const Vec12 fe = b->stiffness() * ue;
    for (int k = 0; k < 12; ++k) f[dofs[k]] += fe[k];
  }
  for (std::size_t j = 0; j < model_->joints.size(); ++j) {
    const auto& jt = model_->joints[j];
    if (!jt.has_stiffness()) continue;
    const int r = map.raw_joint(static_cast<int>(j), 0);
    f.segment(r, jt.coordinates()) += jt.stiffness_as_matrix() * u.segment(r, jt.coordinates());
  }
}

Vec12 LinearStructure::end_forces(const DofMap& map, int element, const Eigen::VectorXd& u) const {
  const FrameElement* b = beam(element);
  if (!b) return Vec12::Zero();
  const auto dofs = element_dofs(map, element);
  Vec12 ue;
  for (int k = 0; k < 12; ++k) ue[k] = u[dofs[k]];
  return b->local_end_forces(ue);
}

Eigen::VectorXd external_force(const Model& m, const DofMap& map) { return external_force(m, map, m.default_loads()); }

}  // namespace beamfea
