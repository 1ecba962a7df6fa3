#pragma once
// The model's elements in their linear form, built once per analysis: beams (LinearBeam, the
// element contract of elements/frame_element.hpp) and joint springs; rigid links and joints
// themselves are constraints handled by the DofMap.
#include <memory>
#include <optional>
#include <vector>

#include "core/assembly.hpp"
#include "core/dense_assembly.hpp"
#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/beam.hpp"

namespace beamfea {

// The section of a beam element, with the shear areas A/ky, A/kz when it is a Timoshenko beam.
BeamSection beam_section(const Model& m, const Element& e);

class LinearStructure {
 public:
  LinearStructure() = default;  // nothing built: rebuild before use
  explicit LinearStructure(const Model& model) { rebuild(model); }
  // Builds `model`'s elements over this structure's: the same as a new LinearStructure's, in the
  // storage of the last build (a sweep whose geometry changes every case). On a throw the structure
  // is unusable until the next rebuild succeeds.
  void rebuild(const Model& model);

  // The raw DOFs of the `add` calls `assemble` makes for `model` over `map`, in their order, known
  // before any element matrix is (SystemAssembler::plan, planned_pattern).
  static AssemblyBlocks assembly_blocks(const Model& model, const DofMap& map);
  // Assembles the elastic stiffness (beams and joint springs) into `assembler`.
  void assemble(const DofMap& map, SystemAssembler& assembler) const;
  // The same into a dense K_ff (small models: the dense path of the stiffness condensation).
  void assemble(const DofMap& map, DenseAssembler& assembler) const;
  // Internal force over raw DOFs for raw displacements u.
  Eigen::VectorXd internal_force(const DofMap& map, const Eigen::VectorXd& u_raw) const;
  // The same written over `f` (its storage kept when it has the size).
  void internal_force(const DofMap& map, const Eigen::VectorXd& u_raw, Eigen::VectorXd& f) const;
  // Raw DOFs of an element: its two nodes' 12 components.
  std::array<int, 12> element_dofs(const DofMap& map, int element) const;
  // Local end forces [N Vy Vz T My Mz] x 2 of a beam element for raw displacements u.
  Vec12 end_forces(const DofMap& map, int element, const Eigen::VectorXd& u_raw) const;

  // The element of a beam, null for a rigid link: a LinearBeam, or the wrapped element of a beam
  // with end releases (solvers/element_factory.hpp).
  const FrameElement* beam(int element) const {
    if (!transformed_.empty() && transformed_[element]) return transformed_[element].get();
    return beams_[element] ? &*beams_[element] : nullptr;
  }
  const Model& model() const { return *model_; }
  // One whole assembly pass of the elastic stiffness into `ka` (begin, assemble, end): its K_ff
  // and K_fp, the shared start of buckling, modal and second-order statics.
  void assemble_stiffness(const DofMap& map, SystemAssembler& ka) const {
    ka.begin();
    assemble(map, ka);
    ka.end();
  }
  // Points the structure at `model`, which must equal the model it was built from in everything
  // the constructor reads (solvers/structure_cache.hpp checks that): `assemble` then reads the
  // joint springs of `model`, which the beams' matrices do not depend on.
  void rebind(const Model& model) { model_ = &model; }

 private:
  template <class Assembler>
  void assemble_into(const DofMap& map, Assembler& assembler) const;
  // The matrix entries one assembly adds (an upper bound: SystemAssembler::expect).
  std::size_t assembly_entries() const;

  const Model* model_ = nullptr;
  std::vector<std::optional<LinearBeam>> beams_;
  // The wrapped elements (empty when the model has none), in place of their plain beams.
  std::vector<std::unique_ptr<FrameElement>> transformed_;
};

// External loads of the default load case over raw DOFs: nodal and joint loads, member loads
// and self-weight as equivalent nodal loads, point masses' weight (solvers/member_loading.hpp).
Eigen::VectorXd external_force(const Model& m, const DofMap& map);

}  // namespace beamfea
