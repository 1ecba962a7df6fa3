#pragma once
// A small dense implementation of the VJM equations of Pashkevich, Klimchik & Chablat (2010),
// "Enhanced stiffness modeling of serial manipulators with passive joints" (Advances in Robot
// Manipulators, InTech), written independently of beamfea's solvers, for the tests only:
//   chain kinematics T = prod of constant transforms, rotations and translations (eqs. 1, 2, 33);
//   loaded equilibrium J_theta^T F = K_theta theta, J_q^T F = 0, g(q, theta) = t (eqs. 6, 7),
//     solved by Newton on the bordered system (the scheme the text suggests after eq. 11);
//   stability (eqs. 18-23): V0^T (K - H^F) V0 positive definite, V0 the null space of [J_q J_theta];
//   loaded Cartesian stiffness (eq. 28): [[K - H^F, -J^T], [J, 0]]^-1 lower-right block = K_F.
// Readings of the garbled equations (eq. 23 signs, eq. 40) as in docs/notes/pashkevich-reference.md.
// Jacobians are analytic (screw form), Hessians H^F = d2(F.g)/dz2 by central differences of them.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

namespace vjm {

using Eigen::Matrix4d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

struct Item {
  enum class Kind { Constant, Rotation, Translation } kind = Kind::Constant;
  int axis = 0;      // local axis 0, 1, 2 for a joint
  int var = -1;      // index in z of a joint
  Matrix4d T = Matrix4d::Identity();  // a constant transform
};

inline Matrix4d rot(int axis, double a) {
  Matrix4d R = Matrix4d::Identity();
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  R(i, i) = std::cos(a);
  R(i, j) = -std::sin(a);
  R(j, i) = std::sin(a);
  R(j, j) = std::cos(a);
  return R;
}
inline Matrix4d tra(int axis, double d) {
  Matrix4d T = Matrix4d::Identity();
  T(axis, 3) = d;
  return T;
}

struct Chain {
  std::vector<Item> items;
  int n = 0;             // number of variables z = [q; theta]
  std::vector<int> rows;  // constrained components of the end position (0 = x, 1 = y, 2 = z)
  MatrixXd K;            // n x n, zero on the passive coordinates q

  void constant(const Matrix4d& T) { items.push_back({Item::Kind::Constant, 0, -1, T}); }
  int rotation(int axis) { items.push_back({Item::Kind::Rotation, axis, n, Matrix4d::Identity()}); return n++; }
  int translation(int axis) { items.push_back({Item::Kind::Translation, axis, n, Matrix4d::Identity()}); return n++; }
  // The 6-D virtual joint of eq. 1: T_3D = Tx Ty Tz Rx Ry Rz; returns the first index.
  int virtual_joint() {
    const int first = n;
    for (int a = 0; a < 3; ++a) translation(a);
    for (int a = 0; a < 3; ++a) rotation(a);
    return first;
  }
  void finish() { K = MatrixXd::Zero(n, n); }

  // End position (constrained rows) and its Jacobian dp/dz: w x (p - o) for a rotation, w for a
  // translation, with w and o the joint's current axis and origin.
  VectorXd position(const VectorXd& z, MatrixXd* J = nullptr) const {
    Matrix4d T = Matrix4d::Identity();
    std::vector<std::pair<int, std::pair<Vector3d, Vector3d>>> axes;
    std::vector<bool> is_rot;
    for (const auto& it : items) {
      if (it.kind == Item::Kind::Constant) {
        T = T * it.T;
        continue;
      }
      axes.push_back({it.var, {T.block<3, 1>(0, it.axis), T.block<3, 1>(0, 3)}});
      is_rot.push_back(it.kind == Item::Kind::Rotation);
      T = T * (it.kind == Item::Kind::Rotation ? rot(it.axis, z[it.var]) : tra(it.axis, z[it.var]));
    }
    const Vector3d p = T.block<3, 1>(0, 3);
    VectorXd out(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) out[r] = p[rows[r]];
    if (J) {
      J->setZero(rows.size(), n);
      for (std::size_t k = 0; k < axes.size(); ++k) {
        const auto& [w, o] = axes[k].second;
        const Vector3d c = is_rot[k] ? Vector3d(w.cross(p - o)) : w;
        for (std::size_t r = 0; r < rows.size(); ++r) (*J)(r, axes[k].first) += c[rows[r]];
      }
    }
    return out;
  }
  MatrixXd jacobian(const VectorXd& z) const {
    MatrixXd J;
    position(z, &J);
    return J;
  }
  // H^F = d2 (F . g) / dz2 (eq. 16), central differences of the analytic Jacobian.
  MatrixXd hessian(const VectorXd& z, const VectorXd& F) const {
    const double h = 1e-6;
    MatrixXd H(n, n);
    for (int j = 0; j < n; ++j) {
      VectorXd zp = z, zm = z;
      zp[j] += h;
      zm[j] -= h;
      H.col(j) = (jacobian(zp).transpose() * F - jacobian(zm).transpose() * F) / (2 * h);
    }
    return 0.5 * (H + H.transpose());
  }
  double energy(const VectorXd& z) const { return 0.5 * z.dot(K * z); }

  // Newton on [K z - J^T F; g(z) - t] = 0, from (z, F). Returns true when converged.
  bool equilibrium(const VectorXd& t, VectorXd& z, VectorXd& F) const {
    const int m = static_cast<int>(rows.size());
    for (int it = 0; it < 50; ++it) {
      const MatrixXd J = jacobian(z);
      VectorXd r(n + m);
      r << K * z - J.transpose() * F, position(z) - t;
      if (r.norm() < 1e-12) return true;
      MatrixXd A = MatrixXd::Zero(n + m, n + m);
      A.topLeftCorner(n, n) = K - hessian(z, F);
      A.topRightCorner(n, m) = -J.transpose();
      A.bottomLeftCorner(m, n) = J;
      const VectorXd d = A.fullPivLu().solve(-r);
      z += d.head(n);
      F += d.tail(m);
    }
    return false;
  }
  // Newton on K z - J^T F = 0 for a given end force F (the passive rows are J_q^T F = 0).
  bool equilibrium_under_force(const VectorXd& F, VectorXd& z) const {
    for (int it = 0; it < 50; ++it) {
      const VectorXd r = K * z - jacobian(z).transpose() * F;
      if (r.norm() < 1e-12) return true;
      z += (K - hessian(z, F)).fullPivLu().solve(-r);
    }
    return false;
  }
  // Smallest eigenvalue of V0^T (K - H^F) V0 (eq. 22/23); > 0: stable.
  double stability_margin(const VectorXd& z, const VectorXd& F) const {
    const MatrixXd J = jacobian(z);
    Eigen::JacobiSVD<MatrixXd> svd(J, Eigen::ComputeFullV);
    const int r = static_cast<int>(rows.size());
    const MatrixXd V0 = svd.matrixV().rightCols(n - r);
    const MatrixXd W = V0.transpose() * (K - hessian(z, F)) * V0;
    return Eigen::SelfAdjointEigenSolver<MatrixXd>(0.5 * (W + W.transpose())).eigenvalues().minCoeff();
  }
  // Loaded Cartesian stiffness K_F of eq. 28 (m x m).
  MatrixXd loaded_stiffness(const VectorXd& z, const VectorXd& F) const {
    const int m = static_cast<int>(rows.size());
    const MatrixXd J = jacobian(z);
    MatrixXd A = MatrixXd::Zero(n + m, n + m);
    A.topLeftCorner(n, n) = K - hessian(z, F);
    A.topRightCorner(n, m) = -J.transpose();
    A.bottomLeftCorner(m, n) = J;
    return A.inverse().bottomRightCorner(m, m);
  }
};

// 6x6 cantilever tip stiffness (eq. 39) in the spring frame, coordinates x y z phi_x phi_y phi_z.
inline MatrixXd cantilever(double E, double G, double A, double Iy, double Iz, double J, double L) {
  MatrixXd K = MatrixXd::Zero(6, 6);
  K(0, 0) = E * A / L;
  K(1, 1) = 12 * E * Iz / (L * L * L);
  K(2, 2) = 12 * E * Iy / (L * L * L);
  K(3, 3) = G * J / L;
  K(4, 4) = 4 * E * Iy / L;
  K(5, 5) = 4 * E * Iz / L;
  K(1, 5) = K(5, 1) = -6 * E * Iz / (L * L);
  K(2, 4) = K(4, 2) = 6 * E * Iy / (L * L);
  return K;
}

// The chain U_p R_a R_a S_p of eq. 33 with one 6-D spring at the end of each link (models B, C):
// z = (q1, q2, theta^1 (6), theta^2 (6), theta^3 (6)); the actuated angles qa1, qa2 and the initial
// universal angle q10 are constants. Rows x, y, z.
inline Chain chain_bc(double qa1, double qa2, double q10, const MatrixXd& Ks, double L = 1.0) {
  Chain c;
  c.rows = {0, 1, 2};
  c.constant(rot(2, q10));
  c.rotation(2);   // q1 (universal, first axis z)
  c.rotation(1);   // q2 (second axis, carried)
  const double qa[3] = {qa1, qa2, 0.0};
  std::vector<int> springs;
  for (int i = 0; i < 3; ++i) {
    c.constant(tra(0, L));
    springs.push_back(c.virtual_joint());
    if (i < 2) c.constant(rot(2, qa[i]));
  }
  c.finish();
  for (int s : springs) c.K.block(s, s, 6, 6) = Ks;
  return c;
}

// Model A in 3-D: universal base, rigid links, revolute actuator springs K about z. z = (q1, q2, th1, th2).
inline Chain chain_a(double qa1, double qa2, double q10, double K, double L = 1.0) {
  Chain c;
  c.rows = {0, 1, 2};
  c.constant(rot(2, q10));
  c.rotation(2);
  c.rotation(1);
  c.constant(tra(0, L));
  c.constant(rot(2, qa1));
  const int t1 = c.rotation(2);
  c.constant(tra(0, L));
  c.constant(rot(2, qa2));
  const int t2 = c.rotation(2);
  c.constant(tra(0, L));
  c.finish();
  c.K(t1, t1) = c.K(t2, t2) = K;
  return c;
}

// Model A, planar R_p R_a R_a R_p (eqs. 34, 35, Table 1): z = (q, th1, th2), rows x, y.
inline Chain chain_a_planar(double K, double L = 1.0) {
  Chain c;
  c.rows = {0, 1};
  c.rotation(2);
  c.constant(tra(0, L));
  const int t1 = c.rotation(2);
  c.constant(tra(0, L));
  const int t2 = c.rotation(2);
  c.constant(tra(0, L));
  c.finish();
  c.K(t1, t1) = c.K(t2, t2) = K;
  return c;
}

}  // namespace vjm
