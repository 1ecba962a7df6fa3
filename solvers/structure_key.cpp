#include "solvers/structure_key.hpp"

#include <bit>
#include <cstdint>

namespace beamfea {

namespace {

// Doubles are equal when their bits are: 0.0 and -0.0 can give results whose zeros differ in sign
// (and a NaN, which no checked model holds, equals itself here and gives the same NaNs again).
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool same(const Vec3& a, const Vec3& b) { return same(a[0], b[0]) && same(a[1], b[1]) && same(a[2], b[2]); }

bool same(const Node& a, const Node& b) { return a.id == b.id && same(a.x, b.x) && a.member == b.member; }
bool same(const Element& a, const Element& b) {
  return a.id == b.id && a.type == b.type && a.nodes == b.nodes && a.material == b.material && a.section == b.section &&
         same(a.orientation, b.orientation) && a.theory == b.theory && a.member == b.member &&
         a.released == b.released && same(a.offsets[0], b.offsets[0]) && same(a.offsets[1], b.offsets[1]);
}
bool same(const Material& a, const Material& b) {
  return a.id == b.id && same(a.E, b.E) && same(a.G, b.G) && same(a.density, b.density);
}
bool same(const Section& a, const Section& b) {
  return a.id == b.id && same(a.A, b.A) && same(a.Iy, b.Iy) && same(a.Iz, b.Iz) && same(a.J, b.J) && same(a.ky, b.ky) &&
         same(a.kz, b.kz);
}
bool same(const Support& a, const Support& b) {
  if (!(a.node == b.node && a.fixed == b.fixed && a.skewed == b.skewed)) return false;
  for (Eigen::Index i = 0; i < 9; ++i)
    if (!same(a.axes.data()[i], b.axes.data()[i])) return false;
  return true;
}
bool same(const Tie& a, const Tie& b) { return a.nodes == b.nodes && a.dofs == b.dofs; }
bool same(const LinearConstraint& a, const LinearConstraint& b) {
  if (a.terms.size() != b.terms.size() || !same(a.value, b.value)) return false;
  for (std::size_t i = 0; i < a.terms.size(); ++i)
    if (!(a.terms[i].dof == b.terms[i].dof && same(a.terms[i].coefficient, b.terms[i].coefficient))) return false;
  return true;
}
bool same(const Prescribed& a, const Prescribed& b) { return a.dof == b.dof && same(a.value, b.value); }

// A joint but its springs.
bool same_kinematics(const Joint& a, const Joint& b) {
  if (!(a.id == b.id && a.type == b.type && a.nodes == b.nodes && a.translations == b.translations &&
        a.axes.size() == b.axes.size()))
    return false;
  for (std::size_t i = 0; i < a.axes.size(); ++i)
    if (!same(a.axes[i], b.axes[i])) return false;
  return true;
}
bool same_springs(const Joint& a, const Joint& b) {
  if (a.stiffness.size() != b.stiffness.size() || a.stiffness_matrix.rows() != b.stiffness_matrix.rows() ||
      a.stiffness_matrix.cols() != b.stiffness_matrix.cols())
    return false;
  for (std::size_t i = 0; i < a.stiffness.size(); ++i)
    if (!same(a.stiffness[i], b.stiffness[i])) return false;
  for (Eigen::Index i = 0; i < a.stiffness_matrix.size(); ++i)
    if (!same(a.stiffness_matrix.data()[i], b.stiffness_matrix.data()[i])) return false;
  return true;
}

template <class T, class Same>
bool all_same(const std::vector<T>& a, const std::vector<T>& b, Same&& same_item) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same_item(a[i], b[i])) return false;
  return true;
}
template <class T>
bool all_same(const std::vector<T>& a, const std::vector<T>& b) {
  return all_same(a, b, [](const T& x, const T& y) { return same(x, y); });
}

// The linear solver the system is solved with (LinearSystem reads it).
bool same_solver(const SolverChoice& a, const SolverChoice& b) {
  return a.type == b.type && same(a.rtol, b.rtol) && a.preconditioner == b.preconditioner &&
         a.max_iterations == b.max_iterations;
}

}  // namespace

bool StructureKey::matches(const Model& model) const {
  if (!set_) return false;
  const bool springs = springs_ == Springs::Included;
  return all_same(nodes_, model.nodes) && all_same(elements_, model.elements) && all_same(materials_, model.materials) &&
         all_same(sections_, model.sections) &&
         all_same(joints_, model.joints,
                  [&](const Joint& a, const Joint& b) { return same_kinematics(a, b) && (!springs || same_springs(a, b)); }) &&
         all_same(supports_, model.supports) && all_same(prescribed_, model.prescribed) && all_same(ties_, model.ties) &&
         all_same(constraints_, model.constraints) && same_solver(solver_, model.solver);
}

void StructureKey::assign(const Model& model) {
  nodes_ = model.nodes;
  elements_ = model.elements;
  materials_ = model.materials;
  sections_ = model.sections;
  joints_ = model.joints;
  supports_ = model.supports;
  prescribed_ = model.prescribed;
  ties_ = model.ties;
  constraints_ = model.constraints;
  solver_ = model.solver;
  if (springs_ == Springs::Excluded) {
    for (auto& j : joints_) {  // not part of the key: no need to hold them
      j.stiffness.clear();
      j.stiffness_matrix.resize(0, 0);
    }
  }
  set_ = true;
}

}  // namespace beamfea
