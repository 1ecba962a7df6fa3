// The element contract suite (elements/frame_element.hpp): every element kind, Euler-Bernoulli and
// Timoshenko, linear and co-rotational, through the same checks: symmetry, six rigid-body modes,
// patch tests of constant strain and constant curvature, force = d(energy) and tangent = d(force)
// by finite differences along the element's own increments (FrameElement::advance), objectivity,
// mass totals, energy = u^T K u / 2, thermal loads, end conditions of the drawn shape.
// A new element kind (or a wrapper) is one more line in ElementKinds; the prismatic member's own
// physics (PlainBeamPhysics) and a wrapper's (ReleasedElementPhysics, OffsetElementPhysics) are suites of
// their own.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>

#include "elements/corotational_beam.hpp"
#include "elements/offset_element.hpp"
#include "elements/released_element.hpp"
#include "elements/span_loads.hpp"

namespace beamfea::element_contract_test {
namespace {

const Vec3 kX1(0.1, -0.2, 0.3);
const Vec3 kX2(1.3, 0.6, -0.3);
const Vec3 kOrientation(0.0, 0.0, 1.0);
constexpr double kDensity = 7.5;

BeamSection test_section(bool shear) {
  BeamSection s;
  s.E = 100.0;
  s.G = 40.0;
  s.A = 1.0;
  s.Iy = 0.05;
  s.Iz = 0.08;
  s.J = 0.1;
  if (shear) {  // Phi_y = 12 E Iz / (G Asy L^2) ~ 1.2: shear flexibility as large as bending's
    s.Asy = 0.8;
    s.Asz = 0.7;
  }
  return s;
}

// End releases of the wrapped kinds (elements/released_element.hpp), in the local DOF order.
enum class Release { None, PinnedStart, Sliding };
Releases release_set(Release r) {
  Releases out{};
  if (r == Release::PinnedStart) out[4] = out[5] = true;                  // start: ry, rz
  if (r == Release::Sliding) out[5] = out[6 + 1] = out[6 + 3] = true;     // start: rz; end: uy, rx
  return out;
}

// Rigid arms of the offset kinds (elements/offset_element.hpp): eccentric, not along the member.
const std::array<Vec3, 2> kArms{Vec3(0.05, 0.1, -0.08), Vec3(-0.1, 0.04, 0.12)};

template <class E, bool Shear, Release R = Release::None, bool Arms = false>
struct Kind {
  static constexpr bool corotational = std::is_same_v<E, CorotationalBeam>;
  static constexpr Release release = R;
  static constexpr bool arms = Arms;
  static std::unique_ptr<FrameElement> make() {
    const std::array<Vec3, 2> o = Arms ? kArms : std::array<Vec3, 2>{Vec3::Zero(), Vec3::Zero()};
    auto beam = std::make_unique<E>(test_section(Shear), kX1 + o[0], kX2 + o[1], kOrientation);
    std::unique_ptr<FrameElement> out;
    if constexpr (R == Release::None) out = std::move(beam);
    else out = std::make_unique<ReleasedElement>(std::move(beam), release_set(R));
    if constexpr (Arms)
      out = std::make_unique<OffsetElement>(std::move(out), o, corotational ? ArmKinematics::Finite : ArmKinematics::Linear);
    return out;
  }
  // The reference position of the drawn member's end `end` and where it is at the state p.
  static Vec3 drawn_end_motion(const NodalPoses& p, int end) {
    const Vec3& X = end == 0 ? kX1 : kX2;
    const Vec3& x = end == 0 ? p.x1 : p.x2;
    const Mat3& Rn = end == 0 ? p.R1 : p.R2;
    if constexpr (!Arms) return x - X;
    else if constexpr (corotational) return x + Rn * kArms[end] - (X + kArms[end]);
    else return x + log_so3(Rn).cross(kArms[end]) - X;
  }
  static int released_count() {
    const Releases r = release_set(R);
    return static_cast<int>(std::count(r.begin(), r.end(), true));
  }
  static BeamSection section() { return test_section(Shear); }
  static std::string name() {
    return std::string(Shear ? "Timoshenko" : "EulerBernoulli") + (corotational ? "Corotational" : "Linear") +
           (R == Release::PinnedStart ? "PinnedStart" : R == Release::Sliding ? "Sliding" : "") + (Arms ? "Offset" : "");
  }
};
using EulerBernoulliLinear = Kind<LinearBeam, false>;
using TimoshenkoLinear = Kind<LinearBeam, true>;
using EulerBernoulliCorotational = Kind<CorotationalBeam, false>;
using TimoshenkoCorotational = Kind<CorotationalBeam, true>;
using EulerBernoulliLinearPinnedStart = Kind<LinearBeam, false, Release::PinnedStart>;
using TimoshenkoLinearSliding = Kind<LinearBeam, true, Release::Sliding>;
using EulerBernoulliCorotationalSliding = Kind<CorotationalBeam, false, Release::Sliding>;
using TimoshenkoCorotationalPinnedStart = Kind<CorotationalBeam, true, Release::PinnedStart>;
using EulerBernoulliLinearOffset = Kind<LinearBeam, false, Release::None, true>;
using TimoshenkoCorotationalOffset = Kind<CorotationalBeam, true, Release::None, true>;
using EulerBernoulliCorotationalPinnedStartOffset = Kind<CorotationalBeam, false, Release::PinnedStart, true>;
using TimoshenkoLinearSlidingOffset = Kind<LinearBeam, true, Release::Sliding, true>;

double norm_max(const Mat12& K) { return K.cwiseAbs().maxCoeff(); }

// A moderate deformation (stretch, bending, twist) superposed on the rigid motion x -> Q x + t.
NodalPoses deformed(const Mat3& Q = Mat3::Identity(), const Vec3& t = Vec3::Zero(), double scale = 1.0) {
  return {Q * kX1 + t, Q * (kX2 + scale * Vec3(0.03, -0.05, 0.04)) + t, Q * exp_so3(scale * Vec3(0.1, -0.05, 0.08)),
          Q * exp_so3(scale * Vec3(-0.07, 0.12, 0.05))};
}

// A rigid motion in the element's own theory: finite for a co-rotational element (x -> Q x + t,
// R = Q), infinitesimal for a linear one (u = t + w x X, theta = w).
NodalPoses rigid(bool corotational, const Vec3& t, const Vec3& w) {
  if (corotational) {
    const Mat3 Q = exp_so3(w);
    return {Q * kX1 + t, Q * kX2 + t, Q, Q};
  }
  return {kX1 + t + w.cross(kX1), kX2 + t + w.cross(kX2), exp_so3(w), exp_so3(w)};
}

// The poses that put the local deformations dl (local axes; node 1 held) on the element at the
// reference: nodal rotations about global axes E0 theta, node 2 moved by E0 du.
NodalPoses local_deformation(const FrameElement& e, const Vec3& du2, const Vec3& theta1, const Vec3& theta2) {
  const Mat3 E0 = e.axes().transpose();
  return {kX1, kX2 + E0 * du2, exp_so3(E0 * theta1), exp_so3(E0 * theta2)};
}

Vec12 fd_energy_gradient(const FrameElement& e, const NodalPoses& p, double h) {
  Vec12 g;
  for (int j = 0; j < 12; ++j) {
    const Vec12 d = h * Vec12::Unit(j);
    g[j] = (e.respond(e.advance(p, d), Evaluate::Force).energy - e.respond(e.advance(p, -d), Evaluate::Force).energy) /
           (2 * h);
  }
  return g;
}

Mat12 fd_force_jacobian(const FrameElement& e, const NodalPoses& p, double h) {
  Mat12 K;
  for (int j = 0; j < 12; ++j) {
    const Vec12 d = h * Vec12::Unit(j);
    K.col(j) = (e.respond(e.advance(p, d), Evaluate::Force).force - e.respond(e.advance(p, -d), Evaluate::Force).force) /
               (2 * h);
  }
  return K;
}

// The contract itself: every kind, the wrappers included.
template <class K>
class ElementContract : public ::testing::Test {};
using ElementKinds =
    ::testing::Types<EulerBernoulliLinear, TimoshenkoLinear, EulerBernoulliCorotational, TimoshenkoCorotational,
                     EulerBernoulliLinearPinnedStart, TimoshenkoLinearSliding, EulerBernoulliCorotationalSliding,
                     TimoshenkoCorotationalPinnedStart, EulerBernoulliLinearOffset, TimoshenkoCorotationalOffset,
                     EulerBernoulliCorotationalPinnedStartOffset, TimoshenkoLinearSlidingOffset>;
struct KindName {
  template <class T>
  static std::string GetName(int) {
    return T::name();
  }
};
TYPED_TEST_SUITE(ElementContract, ElementKinds, KindName);

// The prismatic member's physics (Hooke's law, constant curvature, thermal and member loads):
// the plain kinds, whose ends follow their nodes.
template <class K>
class PlainBeamPhysics : public ::testing::Test {};
using PlainKinds =
    ::testing::Types<EulerBernoulliLinear, TimoshenkoLinear, EulerBernoulliCorotational, TimoshenkoCorotational>;
TYPED_TEST_SUITE(PlainBeamPhysics, PlainKinds, KindName);

TYPED_TEST(ElementContract, StiffnessIsSymmetricAndIsTheTangentAtTheReference) {
  const auto e = TypeParam::make();
  const Mat12& K = e->stiffness();
  EXPECT_LE(norm_max(K - K.transpose()), 1e-13 * norm_max(K));
  const Mat12 Kt = e->respond(e->reference_poses(), Evaluate::ForceAndTangent).tangent;
  EXPECT_LE(norm_max(Kt - K), 1e-12 * norm_max(K));
}

TYPED_TEST(ElementContract, SixRigidBodyModesGiveNoForceAndNoEnergy) {
  const auto e = TypeParam::make();
  // Exactly six zero eigenvalues of the unsupported stiffness, one more per released DOF (each
  // release here frees one deformation mode).
  const Eigen::SelfAdjointEigenSolver<Mat12> es(e->stiffness());
  const auto& ev = es.eigenvalues();  // ascending
  const int zeros = 6 + TypeParam::released_count();
  for (int i = 0; i < zeros; ++i) EXPECT_LE(std::abs(ev[i]), 1e-12 * ev[11]) << "eigenvalue " << i;
  EXPECT_GT(ev[zeros], 1e-6 * ev[11]);
  for (const Vec3& w : {Vec3(0.3, -0.2, 0.5), Vec3(0.0, 0.0, 0.0), Vec3(-1.1, 0.7, 2.0)}) {
    const ElementResponse r = e->respond(rigid(TypeParam::corotational, Vec3(0.4, -0.3, 0.2), w), Evaluate::Force);
    EXPECT_LE(r.force.norm(), 1e-12 * norm_max(e->stiffness()));
    EXPECT_LE(std::abs(r.energy), 1e-12 * norm_max(e->stiffness()));
  }
}

// Constant axial strain: N = EA du/L along the whole element, nothing else.
TYPED_TEST(PlainBeamPhysics, PureStretchGivesTheAxialForceOfHookesLaw) {
  const auto e = TypeParam::make();
  const BeamSection s = TypeParam::section();
  const double L = e->length(), du = 0.01 * L, N = s.E * s.A * du / L;
  const ElementResponse r = e->respond(local_deformation(*e, Vec3(du, 0, 0), Vec3::Zero(), Vec3::Zero()), Evaluate::Force);
  Vec12 want = Vec12::Zero();
  want(0) = -N;
  want(6) = N;
  EXPECT_LE((r.local_end_forces - want).norm(), 1e-12 * N);
  const Vec6 mid = e->section_forces(0.5 * L, r.local_end_forces, ElementLoads{}, CutSide::After);
  EXPECT_NEAR(mid(0), N, 1e-12 * N);
  EXPECT_NEAR(r.energy, 0.5 * N * du, 1e-12 * N * du);
}

// Constant curvature kappa in each plane (end rotations -+ kappa L/2, no deflection): a uniform
// moment E I kappa and no shear, Timoshenko or not (no shear force, no shear strain).
TYPED_TEST(PlainBeamPhysics, ConstantCurvatureGivesAUniformMomentAndNoShear) {
  const auto e = TypeParam::make();
  const BeamSection s = TypeParam::section();
  const double L = e->length(), kappa = 0.2 / L;
  // Bending in x-y: rz = v', rz1 = -kappa L/2, rz2 = +kappa L/2; in x-z: ry = -w'.
  for (const int plane : {0, 1}) {
    const Vec3 t = plane == 0 ? Vec3(0.0, 0.0, kappa * L / 2) : Vec3(0.0, -kappa * L / 2, 0.0);
    const ElementResponse r = e->respond(local_deformation(*e, Vec3::Zero(), -t, t), Evaluate::Force);
    const int k = plane == 0 ? 5 : 4;                                         // Mz or My
    const double M = plane == 0 ? s.E * s.Iz * kappa : -s.E * s.Iy * kappa;  // My = -E Iy w''
    Vec12 want = Vec12::Zero();
    want(k) = -M;
    want(6 + k) = M;
    EXPECT_LE((r.local_end_forces - want).norm(), 1e-10 * std::abs(M)) << r.local_end_forces.transpose();
    const Vec6 cut = e->section_forces(0.3 * L, r.local_end_forces, ElementLoads{}, CutSide::After);
    EXPECT_NEAR(cut(k), M, 1e-10 * std::abs(M));
    EXPECT_NEAR(cut(1), 0.0, 1e-10 * std::abs(M) / L);
    EXPECT_NEAR(cut(2), 0.0, 1e-10 * std::abs(M) / L);
    EXPECT_NEAR(r.energy, 0.5 * M * M * L / (plane == 0 ? s.E * s.Iz : s.E * s.Iy), 1e-10 * std::abs(M) * kappa * L);
  }
}

TYPED_TEST(ElementContract, InternalForceIsTheDerivativeOfStrainEnergy) {
  const auto e = TypeParam::make();
  for (const NodalPoses& p : {deformed(), deformed(exp_so3(Vec3(0.4, -1.2, 0.9)), Vec3(0.5, 0.1, -0.3))}) {
    const Vec12 f = e->respond(p, Evaluate::Force).force;
    const Vec12 g = fd_energy_gradient(*e, p, 1e-6);
    EXPECT_LE((f - g).norm(), 1e-7 * f.norm()) << "force " << f.transpose() << "\nfd    " << g.transpose();
  }
}

TYPED_TEST(ElementContract, TangentMatchesFiniteDifferencesOfInternalForce) {
  const auto e = TypeParam::make();
  // At a deformed state, and at a deformed state carried by a finite rotation and translation.
  for (const NodalPoses& p : {deformed(), deformed(exp_so3(Vec3(0.4, -1.2, 0.9)), Vec3(0.5, 0.1, -0.3))}) {
    const Mat12 K = e->respond(p, Evaluate::ForceAndTangent).tangent;
    const Mat12 Kfd = fd_force_jacobian(*e, p, 1e-6);
    EXPECT_LE(norm_max(K - Kfd), 1e-7 * norm_max(K)) << "tangent\n" << K << "\nfd\n" << Kfd;
  }
}

// Objectivity: a superposed finite rigid rotation Q rotates the forces and keeps the energy and
// the local end forces. A linear element is objective only for infinitesimal rotations (the
// rigid-body test above); the finite case is the co-rotational elements' contract, a suite of
// their own.
template <class K>
class FiniteRotationContract : public ::testing::Test {};
using FiniteRotationKinds =
    ::testing::Types<EulerBernoulliCorotational, TimoshenkoCorotational, EulerBernoulliCorotationalSliding,
                     TimoshenkoCorotationalPinnedStart, TimoshenkoCorotationalOffset, EulerBernoulliCorotationalPinnedStartOffset>;
TYPED_TEST_SUITE(FiniteRotationContract, FiniteRotationKinds, KindName);

TYPED_TEST(FiniteRotationContract, SuperposedRigidRotationRotatesTheForcesAndKeepsTheEnergy) {
  const auto e = TypeParam::make();
  const Mat3 Q = exp_so3(Vec3(0.9, -2.1, 0.6));
  const ElementResponse a = e->respond(deformed(), Evaluate::ForceAndTangent);
  const ElementResponse b = e->respond(deformed(Q, Vec3(1.0, -2.0, 0.5)), Evaluate::ForceAndTangent);
  const Mat12 T = beam_transformation(Q);  // diag(Q, Q, Q, Q)
  EXPECT_NEAR(a.energy, b.energy, 1e-12 * a.energy);
  EXPECT_LE((b.force - T * a.force).norm(), 1e-11 * a.force.norm());
  EXPECT_LE((b.local_end_forces - a.local_end_forces).norm(), 1e-11 * a.local_end_forces.norm());
  EXPECT_LE(norm_max(b.tangent - T * a.tangent * T.transpose()), 1e-11 * norm_max(a.tangent));
}

// The translational mass sums to rho A L along each direction (a rigid translation's kinetic
// energy), consistent and lumped, at the reference and at a rotated state.
TYPED_TEST(ElementContract, MassMatricesCarryTheMembersMassInEachDirection) {
  const auto e = TypeParam::make();
  const double m = kDensity * TypeParam::section().A * e->length();
  for (MassKind kind : {MassKind::Consistent, MassKind::Lumped}) {
    for (const Mat12& M : {e->mass(kind, kDensity), e->mass_at(deformed(exp_so3(Vec3(0.3, 1.0, -0.4))), kind, kDensity)}) {
      EXPECT_LE(norm_max(M - M.transpose()), 1e-14 * norm_max(M));
      for (int d = 0; d < 3; ++d) {
        const Vec12 t = Vec12::Unit(d) + Vec12::Unit(6 + d);
        EXPECT_NEAR(t.dot(M * t), m, 1e-12 * m) << "direction " << d;
      }
    }
  }
}

// Linear elements: energy = u^T K u / 2 exactly; co-rotational ones tend to it at small
// displacements (the next term is of relative order |u|).
TYPED_TEST(ElementContract, EnergyIsHalfTheStiffnessQuadraticFormAtSmallDisplacements) {
  const auto e = TypeParam::make();
  const double scale = TypeParam::corotational ? 1e-6 : 1.0;
  const NodalPoses p = deformed(Mat3::Identity(), Vec3::Zero(), scale);
  Vec12 u;
  u << p.x1 - kX1, log_so3(p.R1), p.x2 - kX2, log_so3(p.R2);
  const double want = 0.5 * u.dot(e->stiffness() * u);
  EXPECT_NEAR(e->respond(p, Evaluate::Force).energy, want, (TypeParam::corotational ? 1e-4 : 1e-12) * want);
}

// Thermal loads reproduce the free thermal deformation: the cantilever (node 1 clamped) under
// them lengthens by alpha dT L and turns its tip by the thermal curvature times L.
TYPED_TEST(PlainBeamPhysics, ThermalLoadsProduceTheFreeThermalDeformation) {
  const auto e = TypeParam::make();
  const double L = e->length(), alpha = 1.2e-5;
  const Temperature t{alpha, 40.0, 25.0, -30.0};
  const Vec12 f = e->thermal_loads(t);
  const Mat12 T = beam_transformation(e->axes());
  const Mat12 k = T * e->stiffness() * T.transpose();  // local axes
  const Vec6 u2 = Eigen::Matrix<double, 6, 6>(k.bottomRightCorner<6, 6>()).lu().solve(Vec6(f.tail<6>()));
  EXPECT_NEAR(u2(0), alpha * 40.0 * L, 1e-10 * alpha * 40.0 * L);
  EXPECT_NEAR(u2(5), -alpha * 25.0 * L, 1e-10 * alpha * 25.0 * L);  // rz = v' , v'' = -alpha dT/dy
  EXPECT_NEAR(u2(4), -alpha * 30.0 * L, 1e-10 * alpha * 30.0 * L);  // ry = -w', w'' = -alpha dT/dz
  EXPECT_NEAR(f(0) + f(6), 0.0, 1e-12 * std::abs(f(6)));            // self-equilibrated
}

TYPED_TEST(ElementContract, GeometricStiffnessIsSymmetricAndLinearInTheEndForces) {
  const auto e = TypeParam::make();
  Vec12 f;
  f << -3.0, 0.4, -0.2, 0.5, 0.7, -0.9, 3.0, -0.4, 0.2, -0.5, 0.3, 1.1;
  const Mat12 kg = e->geometric_stiffness(f);
  EXPECT_LE(norm_max(kg - kg.transpose()), 1e-14 * norm_max(kg));
  EXPECT_LE(norm_max(e->geometric_stiffness(2.5 * f) - 2.5 * kg), 1e-14 * norm_max(kg));
  // The axial term N/L on u (local): tension stiffens.
  const Mat12 T = beam_transformation(e->axes());
  EXPECT_NEAR((T * kg * T.transpose())(0, 0), 3.0 / e->length(), 1e-12);
}

// Member loads: at the reference, the fixed-end forces of dead loads are the negated equivalent
// nodal loads; a uniform load's equivalent loads are w L/2 and w L^2/12 (Przemieniecki 1968).
TYPED_TEST(PlainBeamPhysics, MemberLoadsGiveTheClassicalFixedEndForces) {
  const auto e = TypeParam::make();
  const double L = e->length(), w = 2.0;
  ElementLoads loads;
  loads.distributed.push_back({0.0, L, Vec3(0, -w, 0), Vec3(0, -w, 0)});
  const Vec12 f = e->equivalent_loads(loads);
  EXPECT_NEAR(f(1), -w * L / 2, 1e-12);
  EXPECT_NEAR(f(5), -w * L * L / 12, 1e-12);
  EXPECT_NEAR(f(11), w * L * L / 12, 1e-12);
  EXPECT_LE((e->fixed_end_forces_at(e->reference_poses(), loads) + f).norm(), 1e-13 * f.norm());
}

// The drawn member meets its nodes, or the ends of its rigid arms.
TYPED_TEST(ElementContract, DrawnShapeMeetsTheNodes) {
  const auto e = TypeParam::make();
  const NodalPoses p = deformed(exp_so3(Vec3(0.1, -0.2, 0.15)), Vec3(0.01, 0.02, -0.03));
  EXPECT_LE((e->displacement_at(p, 0.0) - TypeParam::drawn_end_motion(p, 0)).norm(), 1e-14);
  EXPECT_LE((e->displacement_at(p, 1.0) - TypeParam::drawn_end_motion(p, 1)).norm(), 1e-14);
  EXPECT_LE((e->displacement_at(e->reference_poses(), 0.4)).norm(), 1e-15);
}

// A released element's own physics: its released end forces vanish at any state, and a uniform
// load on a member pinned at its start has the propped cantilever's fixed-end forces (Roark's
// Formulas for Stress and Strain, 7th ed., Table 8.1 case 2e: pinned end R = 3wL/8, fixed end
// R = 5wL/8 and M = wL^2/8).
template <class K>
class ReleasedElementPhysics : public ::testing::Test {};
using ReleasedKinds =
    ::testing::Types<EulerBernoulliLinearPinnedStart, TimoshenkoLinearSliding, EulerBernoulliCorotationalSliding,
                     TimoshenkoCorotationalPinnedStart, EulerBernoulliCorotationalPinnedStartOffset, TimoshenkoLinearSlidingOffset>;
TYPED_TEST_SUITE(ReleasedElementPhysics, ReleasedKinds, KindName);

TYPED_TEST(ReleasedElementPhysics, ReleasedEndForcesVanish) {
  const auto e = TypeParam::make();
  const Releases r = release_set(TypeParam::release);
  for (const NodalPoses& p : {deformed(), deformed(exp_so3(Vec3(0.4, -1.2, 0.9)), Vec3(0.5, 0.1, -0.3))}) {
    const ElementResponse a = e->respond(p, Evaluate::Force);
    for (int k = 0; k < 12; ++k) {
      if (r[k]) {
        EXPECT_LE(std::abs(a.local_end_forces[k]), 1e-12 * a.local_end_forces.norm()) << "DOF " << k;
      }
    }
  }
}

template <class K>
class PinnedStartPhysics : public ::testing::Test {};
using PinnedStartKinds = ::testing::Types<EulerBernoulliLinearPinnedStart, TimoshenkoCorotationalPinnedStart>;
TYPED_TEST_SUITE(PinnedStartPhysics, PinnedStartKinds, KindName);

TYPED_TEST(PinnedStartPhysics, UniformLoadGivesTheProppedCantileversFixedEndForces) {
  const auto e = TypeParam::make();
  const double L = e->length(), w = 2.0;
  ElementLoads loads;
  loads.distributed.push_back({0.0, L, Vec3(0, -w, 0), Vec3(0, -w, 0)});
  const Vec12 f = e->equivalent_loads(loads);  // the loads on the nodes
  const double tol = 1e-12 * w * L * L;
  // A Timoshenko member's fixed-end moment is w L^2 / (8 (1 + Phi/4)), Phi = 12 E Iz / (G Asy L^2)
  // (the uniform load's fixed-fixed moments w L^2/12 carried over by the stiffness of
  // Przemieniecki's eq. 5.116, carry-over factor (2 - Phi)/(4 + Phi)); Phi = 0 for Euler-Bernoulli.
  const double phi = TypeParam::section().phi_y(L);
  const double M2 = w * L * L / 8.0 / (1.0 + phi / 4.0);
  EXPECT_NEAR(f(5), 0.0, tol);                  // pinned: no moment
  EXPECT_NEAR(f(11), M2, tol);                  // on the node at the fixed end
  EXPECT_NEAR(f(1) + f(7), -w * L, tol);        // equilibrium
  EXPECT_NEAR(f(1), -(w * L / 2 - M2 / L), tol);  // pinned end: 3wL/8 at Phi = 0
  EXPECT_LE((e->fixed_end_forces_at(e->reference_poses(), loads) + f).norm(), 1e-12 * f.norm());
}

}  // namespace
}  // namespace beamfea::element_contract_test
