#include "elements/span_loads.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace beamfea {

namespace {

// 3-point Gauss-Legendre on [-1, 1]: exact for polynomials of degree <= 5 (Abramowitz & Stegun
// 25.4.30).
constexpr std::array<double, 3> kGaussX{-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr std::array<double, 3> kGaussW{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

// Work-conjugate weights at s of a unit force (rows: local x, y, z) and of a unit moment.
struct ShapeAt {
  double lin1, lin2;          // 1 - xi, xi
  double N1, N2, N3, N4;      // Hermite
  double dN1, dN2, dN3, dN4;  // d/ds
};

ShapeAt shape_at(double L, double s) {
  const double x = s / L, x2 = x * x, x3 = x2 * x;
  return {1.0 - x,
          x,
          1.0 - 3.0 * x2 + 2.0 * x3,
          L * (x - 2.0 * x2 + x3),
          3.0 * x2 - 2.0 * x3,
          L * (x3 - x2),
          (-6.0 * x + 6.0 * x2) / L,
          1.0 - 4.0 * x + 3.0 * x2,
          (6.0 * x - 6.0 * x2) / L,
          3.0 * x2 - 2.0 * x};
}

// Adds the virtual work weights of a force F (local) at s.
void add_force(Vec12& f, const ShapeAt& n, const Vec3& F) {
  f[0] += n.lin1 * F.x();
  f[6] += n.lin2 * F.x();
  f[1] += n.N1 * F.y();
  f[5] += n.N2 * F.y();
  f[7] += n.N3 * F.y();
  f[11] += n.N4 * F.y();
  f[2] += n.N1 * F.z();
  f[4] -= n.N2 * F.z();
  f[8] += n.N3 * F.z();
  f[10] -= n.N4 * F.z();
}

// A moment m works on the section rotations: theta_x linear, theta_z = v', theta_y = -w'.
void add_moment(Vec12& f, const ShapeAt& n, const Vec3& m) {
  f[3] += n.lin1 * m.x();
  f[9] += n.lin2 * m.x();
  f[1] += n.dN1 * m.z();
  f[5] += n.dN2 * m.z();
  f[7] += n.dN3 * m.z();
  f[11] += n.dN4 * m.z();
  f[2] -= n.dN1 * m.y();
  f[4] += n.dN2 * m.y();
  f[8] -= n.dN3 * m.y();
  f[10] += n.dN4 * m.y();
}

// e_x x v in local components.
Vec3 ex_cross(const Vec3& v) { return Vec3(0.0, -v.z(), v.y()); }

}  // namespace

Vec12 equivalent_nodal_loads(double L, const LocalDistributedLoad& q) {
  Vec12 f = Vec12::Zero();
  const double h = q.b - q.a;
  if (!(h > 0.0)) return f;
  for (int g = 0; g < 3; ++g) {
    const double t = 0.5 * (1.0 + kGaussX[g]);
    const double s = q.a + t * h;
    add_force(f, shape_at(L, s), (0.5 * h * kGaussW[g]) * ((1.0 - t) * q.q_a + t * q.q_b));
  }
  return f;
}

Vec12 equivalent_nodal_loads(double L, const LocalPointLoad& p) {
  Vec12 f = Vec12::Zero();
  const ShapeAt n = shape_at(L, p.a);
  add_force(f, n, p.force);
  add_moment(f, n, p.moment);
  return f;
}

Vec12 equivalent_nodal_loads(double L, const ElementLoads& loads) {
  Vec12 f = Vec12::Zero();
  for (const auto& q : loads.distributed) f += equivalent_nodal_loads(L, q);
  for (const auto& p : loads.points) f += equivalent_nodal_loads(L, p);
  return f;
}

Vec12 fixed_end_forces(double L, const ElementLoads& loads) { return -equivalent_nodal_loads(L, loads); }

Vec6 section_forces_at(double s, const Vec12& F, const ElementLoads& loads, CutSide side) {
  Vec3 force = -F.head<3>();
  Vec3 moment = -F.segment<3>(3) + s * ex_cross(F.head<3>());
  for (const auto& q : loads.distributed) {
    const double hi = std::min(q.b, s);
    const double h = hi - q.a;
    if (!(h > 0.0) || !(q.b > q.a)) continue;
    for (int g = 0; g < 3; ++g) {
      const double t = q.a + 0.5 * (1.0 + kGaussX[g]) * h;    // position of the Gauss point
      const double u = (t - q.a) / (q.b - q.a);
      const Vec3 qt = (1.0 - u) * q.q_a + u * q.q_b;
      const double w = 0.5 * h * kGaussW[g];
      force -= w * qt;
      moment -= w * (t - s) * ex_cross(qt);
    }
  }
  for (const auto& p : loads.points) {
    const bool included = side == CutSide::After ? p.a <= s : p.a < s;
    if (!included) continue;
    force -= p.force;
    moment -= (p.a - s) * ex_cross(p.force) + p.moment;
  }
  Vec6 out;
  out << force, moment;
  return out;
}

std::vector<double> load_discontinuities(double L, const ElementLoads& loads) {
  std::vector<double> x;
  for (const auto& q : loads.distributed) {
    if (q.a > 0.0 && q.a < L) x.push_back(q.a);
    if (q.b > 0.0 && q.b < L) x.push_back(q.b);
  }
  for (const auto& p : loads.points)
    if (p.a > 0.0 && p.a < L) x.push_back(p.a);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  return x;
}

namespace {

// Coefficients of a force-like shape from the local equivalent loads of unit loads along x and y.
DeadLoadTerm force_term(const Vec3& Q, const Vec12& fx, const Vec12& fy) {
  DeadLoadTerm t;
  t.Q = Q;
  t.alpha[0] = fy[1];
  t.alpha[1] = fy[7];
  t.gamma[0] = fx[0];
  t.gamma[1] = fx[6];
  t.beta[0] = fy[5];   // q along y: M = beta e x y = beta z
  t.beta[1] = fy[11];
  return t;
}

}  // namespace

std::vector<DeadLoadTerm> dead_load_terms(double L, double a, double b, const Vec3& q_a, const Vec3& q_b) {
  std::vector<DeadLoadTerm> terms;
  if (!(b > a)) return terms;
  // Shape (1 - t) carries q_a, shape t carries q_b.
  for (int k = 0; k < 2; ++k) {
    const Vec3& Q = k == 0 ? q_a : q_b;
    if (Q.isZero(0.0)) continue;
    const double wa = k == 0 ? 1.0 : 0.0, wb = 1.0 - wa;
    const Vec12 fx = equivalent_nodal_loads(L, LocalDistributedLoad{a, b, Vec3(wa, 0, 0), Vec3(wb, 0, 0)});
    const Vec12 fy = equivalent_nodal_loads(L, LocalDistributedLoad{a, b, Vec3(0, wa, 0), Vec3(0, wb, 0)});
    terms.push_back(force_term(Q, fx, fy));
  }
  return terms;
}

std::vector<DeadLoadTerm> dead_load_terms(double L, double a, const Vec3& force, const Vec3& moment) {
  std::vector<DeadLoadTerm> terms;
  if (!force.isZero(0.0)) {
    const Vec12 fx = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3::UnitX(), Vec3::Zero()});
    const Vec12 fy = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3::UnitY(), Vec3::Zero()});
    terms.push_back(force_term(force, fx, fy));
  }
  if (!moment.isZero(0.0)) {
    const Vec12 mx = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3::Zero(), Vec3::UnitX()});
    const Vec12 mz = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3::Zero(), Vec3::UnitZ()});
    DeadLoadTerm t;
    t.moment = true;
    t.Q = moment;
    t.gamma[0] = mx[3];
    t.gamma[1] = mx[9];
    t.alpha[0] = -mz[1];  // eps: m along z gives F = eps e x z = -eps y
    t.alpha[1] = -mz[7];
    t.beta[0] = mz[5];    // delta
    t.beta[1] = mz[11];
    terms.push_back(t);
  }
  return terms;
}

Vec12 dead_load_vector(const std::vector<DeadLoadTerm>& terms, const Vec3& e) {
  Vec12 f = Vec12::Zero();
  for (const auto& t : terms) {
    const double eq = e.dot(t.Q);
    const Vec3 along = eq * e, across = t.Q - along;
    for (int i = 0; i < 2; ++i) {
      if (!t.moment) {
        f.segment<3>(6 * i) += t.alpha[i] * across + t.gamma[i] * along;
        f.segment<3>(6 * i + 3) += t.beta[i] * e.cross(t.Q);
      } else {
        f.segment<3>(6 * i) += t.alpha[i] * e.cross(t.Q);
        f.segment<3>(6 * i + 3) += t.beta[i] * across + t.gamma[i] * along;
      }
    }
  }
  return f;
}

Eigen::Matrix<double, 12, 3> dead_load_derivative(const std::vector<DeadLoadTerm>& terms, const Vec3& e, double ln) {
  Eigen::Matrix<double, 12, 3> D = Eigen::Matrix<double, 12, 3>::Zero();
  const Mat3 P = (Mat3::Identity() - e * e.transpose()) / ln;  // de/dd
  for (const auto& t : terms) {
    // d[(e.Q) e] = [e Q^T + (e.Q) I] de;  d[e x Q] = -[Q]x de
    const Mat3 dAlong = (e * t.Q.transpose() + e.dot(t.Q) * Mat3::Identity()) * P;
    const Mat3 dCross = -skew(t.Q) * P;
    for (int i = 0; i < 2; ++i) {
      if (!t.moment) {
        D.block<3, 3>(6 * i, 0) += (t.gamma[i] - t.alpha[i]) * dAlong;
        D.block<3, 3>(6 * i + 3, 0) += t.beta[i] * dCross;
      } else {
        D.block<3, 3>(6 * i, 0) += t.alpha[i] * dCross;
        D.block<3, 3>(6 * i + 3, 0) += (t.gamma[i] - t.beta[i]) * dAlong;
      }
    }
  }
  return D;
}

}  // namespace beamfea
