#include "solvers/superelement.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/assembly.hpp"
#include "core/dof_map.hpp"
#include "core/errors.hpp"
#include "solvers/generalized_eigen.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/mass_matrix.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

namespace {

// The eigen-solver's shift below the fixed-interface spectrum: sigma = -kShiftRelative *
// min_i(K_ii / M_ii), the choice of the modal analysis (solvers/modal.cpp, where it is justified).
constexpr double kShiftRelative = 1e-9;
// A saddle point whose residual exceeds this multiple of |S| |X| (plus one) is nearly singular
// (solvers/condensation.cpp's test).
constexpr double kSaddleResidualRelative = 1e-8;

// The interface in the reduction's coordinates z (r of them, length-scaled: rotations x L):
// z = A u over the free DOFs, z = Q d over the interface DOFs d (6n), d = P z for the directions
// the interface can move.
struct InterfaceRows {
  Eigen::MatrixXd A, Q, P;
  std::vector<int> picked;    // per row: the free DOF it picks alone (empty: the rows are not picks)
  std::vector<double> coef;   // per row: A's entry there
  std::vector<int> held;      // interface DOFs (0 .. 6n-1) that cannot move at all
};

Eigen::VectorXd free_column_scale(const Model& model, const DofMap& map, double L) {
  Eigen::VectorXd c(map.free_size());
  for (int f = 0; f < map.free_size(); ++f) {
    const DofRef& d = map.free_dofs()[static_cast<std::size_t>(f)];
    const bool rotation = d.owner == DofRef::Owner::Node ? d.comp >= 3 : !model.joints[d.index].is_translation(d.comp);
    c[f] = rotation ? 1.0 / L : 1.0;
  }
  return c;
}

InterfaceRows interface_rows(const Model& model, const DofMap& map, const std::vector<int>& interface,
                             const SuperelementOptions& options) {
  const double L = model.length_scale();
  const int nf = map.free_size();
  const Eigen::Index nd = 6 * static_cast<Eigen::Index>(interface.size());
  Eigen::MatrixXd raw = Eigen::MatrixXd::Zero(nd, nf);
  Eigen::VectorXd s(nd);
  for (Eigen::Index k = 0; k < nd; ++k) {
    const int comp = static_cast<int>(k % 6);
    s[k] = comp < 3 ? 1.0 : L;
    for (SparseRowMatrix::InnerIterator it(map.T_free(), map.raw_node(interface[static_cast<std::size_t>(k / 6)], comp)); it; ++it)
      raw(k, it.col()) += it.value();
  }
  const Eigen::MatrixXd scaled = s.asDiagonal() * raw * free_column_scale(model, map, L).asDiagonal();
  const Eigen::VectorXd norms = scaled.rowwise().norm();
  const double largest = nd > 0 ? norms.maxCoeff() : 0.0;
  InterfaceRows out;
  std::vector<int> moving;
  for (Eigen::Index k = 0; k < nd; ++k) {
    if (norms[k] <= options.motion_tolerance * largest || largest == 0.0) out.held.push_back(static_cast<int>(k));
    else moving.push_back(static_cast<int>(k));
  }
  // Picks: each moving row has one nonzero, in a free DOF no other row touches.
  std::vector<int> owner(static_cast<std::size_t>(nf), -1);
  bool picks = true;
  for (const int k : moving) {
    int col = -1;
    for (int j = 0; j < nf && picks; ++j)
      if (raw(k, j) != 0.0) {
        if (col >= 0 || owner[static_cast<std::size_t>(j)] >= 0) picks = false;
        col = j;
      }
    if (!picks) break;
    owner[static_cast<std::size_t>(col)] = k;
    out.picked.push_back(col);
    out.coef.push_back(s[k] * raw(k, col));
  }
  if (picks) {
    const Eigen::Index r = static_cast<Eigen::Index>(moving.size());
    out.A = Eigen::MatrixXd::Zero(r, nf);
    out.Q = Eigen::MatrixXd::Zero(r, nd);
    out.P = Eigen::MatrixXd::Zero(nd, r);
    for (Eigen::Index i = 0; i < r; ++i) {
      const int k = moving[static_cast<std::size_t>(i)];
      out.A(i, out.picked[static_cast<std::size_t>(i)]) = out.coef[static_cast<std::size_t>(i)];
      out.Q(i, k) = s[k];
      out.P(k, i) = 1.0 / s[k];
    }
    return out;
  }
  // The directions the interface can move: the left singular vectors U_r of the scaled rows.
  out.picked.clear();
  out.coef.clear();
  // An SVD of the rows themselves (not an eigen-decomposition of their Gram matrix, whose rounding,
  // eps times the largest, would hide the zero singular values of dependent rows).
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullU);
  const Eigen::VectorXd& sv = svd.singularValues();  // descending
  Eigen::Index r = 0;
  while (r < sv.size() && sv[r] > options.motion_tolerance * sv[0]) ++r;
  const Eigen::MatrixXd U = svd.matrixU().leftCols(r);
  out.Q = U.transpose() * s.asDiagonal();
  out.P = s.cwiseInverse().asDiagonal() * U;
  out.A = out.Q * raw;
  return out;
}

// The static basis X (free x r, A X = I) and K_z: Guyan's partition when the rows are picks,
// the saddle point otherwise. False: holding the interface leaves a mechanism.
bool static_basis(const SparseMatrix& K, const InterfaceRows& rows, Eigen::MatrixXd& X, Eigen::MatrixXd& Kz,
                  SparseMatrix& K_ii, std::vector<int>& interior) {
  const int nf = static_cast<int>(K.rows());
  const Eigen::Index r = rows.A.rows();
  if (!rows.picked.empty() || r == 0) {
    // Guyan: interior DOFs i (those not picked), interface DOFs b (picked, scaled by D = coef).
    std::vector<int> slot(static_cast<std::size_t>(nf), -1);  // interior index, or -(row + 2)
    for (Eigen::Index k = 0; k < r; ++k) slot[static_cast<std::size_t>(rows.picked[static_cast<std::size_t>(k)])] = -static_cast<int>(k) - 2;
    interior.clear();
    for (int j = 0; j < nf; ++j)
      if (slot[static_cast<std::size_t>(j)] == -1) {
        slot[static_cast<std::size_t>(j)] = static_cast<int>(interior.size());
        interior.push_back(j);
      }
    const Eigen::Index ni = static_cast<Eigen::Index>(interior.size());
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(K.nonZeros()));
    Eigen::MatrixXd K_ib = Eigen::MatrixXd::Zero(ni, r), K_bb = Eigen::MatrixXd::Zero(r, r);
    for (int j = 0; j < K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
        const int a = slot[static_cast<std::size_t>(it.row())], b = slot[static_cast<std::size_t>(j)];
        if (a >= 0 && b >= 0) t.emplace_back(a, b, it.value());
        else if (a >= 0) K_ib(a, -b - 2) += it.value();
        else if (b < 0) K_bb(-a - 2, -b - 2) += it.value();
      }
    K_ii.resize(ni, ni);
    K_ii.setFromTriplets(t.begin(), t.end());
    K_ii.makeCompressed();
    Eigen::VectorXd d_inv(r);
    for (Eigen::Index k = 0; k < r; ++k) d_inv[k] = 1.0 / rows.coef[static_cast<std::size_t>(k)];
    K_ib = K_ib * d_inv.asDiagonal();
    Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(ni, r);
    if (ni > 0) {
      const std::unique_ptr<LinearSolver> solver = make_linear_solver();
      if (solver->compute(K_ii) != FactorStatus::Succeeded) return false;
      if (r > 0) solver->solve(K_ib, Y);
      if (!Y.allFinite()) return false;
    }
    X = Eigen::MatrixXd::Zero(nf, r);
    for (Eigen::Index k = 0; k < r; ++k) X(rows.picked[static_cast<std::size_t>(k)], k) = d_inv[k];
    for (Eigen::Index i = 0; i < ni; ++i) X.row(interior[static_cast<std::size_t>(i)]) = -Y.row(i);
    Kz = d_inv.asDiagonal() * K_bb * d_inv.asDiagonal() - K_ib.transpose() * Y;
    Kz = 0.5 * (Kz + Kz.transpose()).eval();
    return true;
  }
  // The saddle point [K A^T; A 0] (indefinite: LU).
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(K.nonZeros() + 2 * rows.A.size()));
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) t.emplace_back(static_cast<int>(it.row()), j, it.value());
  for (Eigen::Index k = 0; k < r; ++k)
    for (int j = 0; j < nf; ++j)
      if (rows.A(k, j) != 0.0) {
        t.emplace_back(nf + static_cast<int>(k), j, rows.A(k, j));
        t.emplace_back(j, nf + static_cast<int>(k), rows.A(k, j));
      }
  SparseMatrix S(nf + r, nf + r);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  const std::unique_ptr<LinearSolver> lu = make_linear_solver(SolverOptions{.backend = SolverBackend::Umfpack});
  if (lu->compute(S) != FactorStatus::Succeeded) return false;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf + r, r);
  rhs.bottomRows(r).setIdentity();
  Eigen::MatrixXd Z;
  lu->solve(rhs, Z);
  if (!Z.allFinite()) return false;
  if ((S * Z - rhs).norm() > kSaddleResidualRelative * (Eigen::MatrixXd(S.cwiseAbs() * Z.cwiseAbs()).norm() + 1.0))
    return false;
  X = Z.topRows(nf);
  const Eigen::MatrixXd L = Z.bottomRows(r);
  Kz = -0.5 * (L + L.transpose());
  return true;
}

// The shift below the spectrum of (K, M) (nullopt: no mass).
std::optional<double> shift_below(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::VectorXd dK = K.diagonal(), dM = M.diagonal();
  double ratio = std::numeric_limits<double>::infinity(), m_max = 0.0;
  for (Eigen::Index i = 0; i < dK.size(); ++i) {
    m_max = std::max(m_max, dM[i]);
    if (dM[i] > 0.0 && dK[i] > 0.0) ratio = std::min(ratio, dK[i] / dM[i]);
  }
  if (!(m_max > 0.0)) return std::nullopt;
  if (!std::isfinite(ratio)) ratio = 1.0;
  return -kShiftRelative * ratio;
}

SparseMatrix principal_block(const SparseMatrix& A, const std::vector<int>& index) {
  std::vector<int> slot(static_cast<std::size_t>(A.rows()), -1);
  for (std::size_t i = 0; i < index.size(); ++i) slot[static_cast<std::size_t>(index[i])] = static_cast<int>(i);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int a = slot[static_cast<std::size_t>(it.row())], b = slot[static_cast<std::size_t>(j)];
      if (a >= 0 && b >= 0) t.emplace_back(a, b, it.value());
    }
  const Eigen::Index n = static_cast<Eigen::Index>(index.size());
  SparseMatrix B(n, n);
  B.setFromTriplets(t.begin(), t.end());
  B.makeCompressed();
  return B;
}

}  // namespace

void SuperelementOptions::validate() const {
  if (modes < 0) throw Error("SuperelementOptions: modes must not be negative");
  if (!(rank_tolerance > 0.0) || !(motion_tolerance > 0.0)) throw Error("SuperelementOptions: tolerances must be positive");
}

const char* to_string(SuperelementStatus s) {
  switch (s) {
    case SuperelementStatus::Succeeded: return "ok";
    case SuperelementStatus::Mechanism: return "mechanism";
    case SuperelementStatus::NoMass: return "no mass";
    case SuperelementStatus::Failed: return "failed";
  }
  return "?";
}

SuperelementResult reduce_superelement(const Model& model, const std::vector<int>& interface,
                                       const SuperelementOptions& options) {
  options.validate();
  SuperelementResult res;
  const DofMap map(model);
  const LinearStructure structure(model);
  res.free_dofs = map.free_size();
  SystemAssembler ka(map, SystemAssembler::Passes::One), ma(map, SystemAssembler::Passes::One);
  structure.assemble_stiffness(map, ka);
  const SparseMatrix& K = ka.K_ff();
  // The mass is assembled only where the model has some (a density, a point mass): a stiffness-only
  // superelement costs one assembly, one factorisation and the solves.
  const bool any_mass = !model.masses.empty() ||
                        std::any_of(model.materials.begin(), model.materials.end(), [](const Material& m) { return m.density > 0.0; });
  SparseMatrix M(map.free_size(), map.free_size());
  if (any_mass) {
    ma.begin();
    assemble_mass(structure, map, options.mass, ma);
    ma.end();
    M = ma.K_ff();
  }
  res.has_mass = M.nonZeros() > 0 && M.coeffs().cwiseAbs().maxCoeff() > 0.0;

  const InterfaceRows rows = interface_rows(model, map, interface, options);
  const Eigen::Index nd = 6 * static_cast<Eigen::Index>(interface.size());
  for (const int k : rows.held)
    res.held_dofs.push_back(model.describe(DofRef{DofRef::Owner::Node, interface[static_cast<std::size_t>(k / 6)], k % 6}));

  Eigen::MatrixXd X, Kz;
  SparseMatrix K_ii;
  std::vector<int> interior;
  if (!static_basis(K, rows, X, Kz, K_ii, interior)) {
    res.status = SuperelementStatus::Mechanism;
    res.message = "superelement: holding the interface nodes still leaves a mechanism (a part of the structure "
                  "that neither the interface nor a support holds)";
    return res;
  }

  // Craig-Bampton: the fixed-interface modes Phi (free x m), A Phi = 0.
  Eigen::MatrixXd Phi;
  Eigen::VectorXd lambda;
  if (options.modes > 0) {
    if (!res.has_mass) {
      res.status = SuperelementStatus::NoMass;
      res.message = "superelement: fixed-interface modes need mass (give the materials a density or add point masses)";
      return res;
    }
    SparseMatrix Kf, Mf;
    Eigen::MatrixXd N;  // free <- fixed-interface coordinates
    if (!rows.picked.empty() || rows.A.rows() == 0) {
      Kf = K_ii;
      Mf = principal_block(M, interior);
    } else {
      // The null space of A (dense: interfaces whose DOFs are not free DOFs of their own).
      const Eigen::HouseholderQR<Eigen::MatrixXd> qr(rows.A.transpose());
      const Eigen::MatrixXd Qfull = qr.householderQ();
      N = Qfull.rightCols(Qfull.cols() - rows.A.rows());
      Kf = Eigen::MatrixXd(N.transpose() * K * N).sparseView();
      Mf = Eigen::MatrixXd(N.transpose() * M * N).sparseView();
    }
    const int available = static_cast<int>(Kf.rows());
    const int count = std::min(options.modes, available);
    const std::optional<double> sigma = shift_below(Kf, Mf);
    if (count == 0 || !sigma) {
      res.status = SuperelementStatus::NoMass;
      res.message = "superelement: the interior of the superelement has no mass or no free DOF for fixed-interface modes";
      return res;
    }
    GeneralizedEigenPairs eig;
    try {
      eig = nearest_generalized_eigenpairs(Kf, Mf, count, *sigma);
    } catch (const Error& e) {
      res.status = SuperelementStatus::Failed;
      res.message = std::string("superelement: fixed-interface modes: ") + e.what();
      return res;
    }
    if (!eig.converged) {
      res.status = SuperelementStatus::Failed;
      res.message = "superelement: fixed-interface modes: " + eig.message;
      return res;
    }
    lambda = eig.values;
    if (N.size() > 0) {
      Phi = N * eig.vectors;
    } else {
      Phi = Eigen::MatrixXd::Zero(map.free_size(), eig.vectors.cols());
      for (std::size_t i = 0; i < interior.size(); ++i) Phi.row(interior[i]) = eig.vectors.row(static_cast<Eigen::Index>(i));
    }
  }

  const Eigen::Index m = lambda.size(), total = nd + m;
  res.stiffness = Eigen::MatrixXd::Zero(total, total);
  res.stiffness.topLeftCorner(nd, nd) = rows.Q.transpose() * Kz * rows.Q;
  for (Eigen::Index j = 0; j < m; ++j) res.stiffness(nd + j, nd + j) = lambda[j];
  res.frequencies.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) res.frequencies[j] = std::sqrt(std::max(lambda[j], 0.0)) / (2.0 * std::numbers::pi);
  if (res.has_mass) {
    Eigen::MatrixXd B(map.free_size(), total);
    B.leftCols(nd) = X * rows.Q;
    if (m > 0) B.rightCols(m) = Phi;
    const Eigen::MatrixXd MB = M * B;
    res.mass = B.transpose() * MB;
    res.mass = 0.5 * (res.mass + res.mass.transpose()).eval();
  } else {
    res.mass = Eigen::MatrixXd::Zero(total, total);
  }

  // Rigid-body modes: the null space of K_z (length-scaled coordinates z), carried to d = P z.
  if (Kz.rows() > 0) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Kz);
    const double top = es.eigenvalues().cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < Kz.rows(); ++k)
      if (std::abs(es.eigenvalues()[k]) <= options.rank_tolerance * top || top == 0.0) {
        Eigen::VectorXd v = Eigen::VectorXd::Zero(total);
        v.head(nd) = rows.P * es.eigenvectors().col(k);
        res.rigid_body_modes.push_back(std::move(v));
      }
  }
  res.status = SuperelementStatus::Succeeded;
  res.message = fmt::format("superelement: {} free DOFs reduced to {} ({} interface node{}{}){}{}", res.free_dofs, total,
                            interface.size(), interface.size() == 1 ? "" : "s",
                            m > 0 ? fmt::format(", {} fixed-interface modes, lowest {:.6g} Hz", m, res.frequencies[0]) : "",
                            res.rigid_body_modes.empty() ? "" : fmt::format(", {} rigid-body modes", res.rigid_body_modes.size()),
                            res.held_dofs.empty() ? "" : fmt::format(", {} interface DOFs held", res.held_dofs.size()));
  return res;
}

Model sub_model(const Model& model, const std::vector<int>& members, std::vector<int>& node_of) {
  Model sub;
  std::vector<char> in_member(model.members.size(), 0);
  for (const int mi : members) in_member[static_cast<std::size_t>(mi)] = 1;
  node_of.assign(model.nodes.size(), -1);
  auto keep_node = [&](int n) {
    if (node_of[static_cast<std::size_t>(n)] < 0) node_of[static_cast<std::size_t>(n)] = sub.add_node(model.nodes[static_cast<std::size_t>(n)]);
    return node_of[static_cast<std::size_t>(n)];
  };
  for (const auto& mat : model.materials) sub.add_material(mat);
  for (const auto& sec : model.sections) sub.add_section(sec);
  std::vector<int> member_of(model.members.size(), -1), element_of(model.elements.size(), -1);
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const Element& el = model.elements[e];
    if (el.member < 0 || !in_member[static_cast<std::size_t>(el.member)]) continue;
    Element copy = el;
    for (int k = 0; k < 2; ++k) copy.nodes[k] = keep_node(el.nodes[k]);
    element_of[e] = static_cast<int>(sub.elements.size());
    sub.elements.push_back(std::move(copy));
  }
  for (const int mi : members) {
    Member copy = model.members[static_cast<std::size_t>(mi)];
    for (int k = 0; k < 2; ++k) copy.nodes[k] = keep_node(copy.nodes[k]);
    for (int& e : copy.elements) e = element_of[static_cast<std::size_t>(e)];
    member_of[static_cast<std::size_t>(mi)] = sub.add_member(std::move(copy));
  }
  for (auto& el : sub.elements) el.member = member_of[static_cast<std::size_t>(el.member)];
  auto kept = [&](int n) { return node_of[static_cast<std::size_t>(n)] >= 0; };
  for (const auto& j : model.joints)
    if (kept(j.nodes[0]) && kept(j.nodes[1])) {
      Joint copy = j;
      for (int k = 0; k < 2; ++k) copy.nodes[k] = node_of[static_cast<std::size_t>(j.nodes[k])];
      sub.add_joint(std::move(copy));
    }
  // A DOF of a joint kept: its index in the sub-model (joints keep their order), or -1.
  std::vector<int> joint_of(model.joints.size(), -1);
  for (std::size_t j = 0, k = 0; j < model.joints.size(); ++j)
    if (kept(model.joints[j].nodes[0]) && kept(model.joints[j].nodes[1])) joint_of[j] = static_cast<int>(k++);
  auto map_dof = [&](DofRef d) -> std::optional<DofRef> {
    const std::vector<int>& of = d.owner == DofRef::Owner::Node ? node_of : joint_of;
    if (of[static_cast<std::size_t>(d.index)] < 0) return std::nullopt;
    d.index = of[static_cast<std::size_t>(d.index)];
    return d;
  };
  for (const auto& s : model.supports)
    if (kept(s.node)) {
      Support copy = s;
      copy.node = node_of[static_cast<std::size_t>(s.node)];
      sub.supports.push_back(copy);
    }
  for (const auto& p : model.prescribed)
    if (const auto d = map_dof(p.dof)) sub.prescribed.push_back({*d, p.value});
  for (const auto& t : model.ties)
    if (kept(t.nodes[0]) && kept(t.nodes[1]))
      sub.ties.push_back({{node_of[static_cast<std::size_t>(t.nodes[0])], node_of[static_cast<std::size_t>(t.nodes[1])]}, t.dofs});
  for (const auto& c : model.constraints) {
    LinearConstraint copy = c;
    bool all = true;
    for (auto& term : copy.terms) {
      const auto d = map_dof(term.dof);
      if (!d) all = false;
      else term.dof = *d;
    }
    if (all) sub.constraints.push_back(std::move(copy));
  }
  for (const auto& pm : model.masses)
    if (kept(pm.node)) {
      PointMass copy = pm;
      copy.node = node_of[static_cast<std::size_t>(pm.node)];
      sub.masses.push_back(copy);
    }
  return sub;
}

}  // namespace beamfea
