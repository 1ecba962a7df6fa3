#include "elements/geometric_stiffness.hpp"

#include <cassert>
#include <utility>

namespace beamfea {

Mat12 beam_local_geometric_stiffness(double L, double A, double Iy, double Iz, const Vec12& f) {
  assert(L > 0.0 && A > 0.0);
  // McGuire, Gallagher & Ziemian (2000), eq. 9.18, symbols as in the book.
  const double Fx2 = 0.5 * (f(6) - f(0));
  const double Mx2 = 0.5 * (f(9) - f(3));
  const double My1 = f(4), Mz1 = f(5), My2 = f(10), Mz2 = f(11);
  const double Ip_A = (Iy + Iz) / A;

  Mat12 kg = Mat12::Zero();
  // Upper triangle, off the diagonal; mirrored below.
  kg(0, 6) = -Fx2 / L;

  kg(1, 3) = My1 / L;
  kg(1, 4) = Mx2 / L;
  kg(1, 5) = Fx2 / 10.0;
  kg(1, 7) = -6.0 * Fx2 / (5.0 * L);
  kg(1, 9) = My2 / L;
  kg(1, 10) = -Mx2 / L;
  kg(1, 11) = Fx2 / 10.0;

  kg(2, 3) = Mz1 / L;
  kg(2, 4) = -Fx2 / 10.0;
  kg(2, 5) = Mx2 / L;
  kg(2, 8) = -6.0 * Fx2 / (5.0 * L);
  kg(2, 9) = Mz2 / L;
  kg(2, 10) = -Fx2 / 10.0;
  kg(2, 11) = -Mx2 / L;

  kg(3, 4) = -(2.0 * Mz1 - Mz2) / 6.0;
  kg(3, 5) = (2.0 * My1 - My2) / 6.0;
  kg(3, 7) = -My1 / L;
  kg(3, 8) = -Mz1 / L;
  kg(3, 9) = -Fx2 * Ip_A / L;
  kg(3, 10) = -(Mz1 + Mz2) / 6.0;
  kg(3, 11) = (My1 + My2) / 6.0;

  kg(4, 7) = -Mx2 / L;
  kg(4, 8) = Fx2 / 10.0;
  kg(4, 9) = -(Mz1 + Mz2) / 6.0;
  kg(4, 10) = -Fx2 * L / 30.0;
  kg(4, 11) = Mx2 / 2.0;

  kg(5, 7) = -Fx2 / 10.0;
  kg(5, 8) = -Mx2 / L;
  kg(5, 9) = (My1 + My2) / 6.0;
  kg(5, 10) = -Mx2 / 2.0;
  kg(5, 11) = -Fx2 * L / 30.0;

  kg(7, 9) = -My2 / L;
  kg(7, 10) = Mx2 / L;
  kg(7, 11) = -Fx2 / 10.0;

  kg(8, 9) = -Mz2 / L;
  kg(8, 10) = Fx2 / 10.0;
  kg(8, 11) = Mx2 / L;

  kg(9, 10) = (Mz1 - 2.0 * Mz2) / 6.0;
  kg(9, 11) = -(My1 - 2.0 * My2) / 6.0;

  kg = (kg + kg.transpose()).eval();

  kg(0, 0) = kg(6, 6) = Fx2 / L;
  kg(1, 1) = kg(2, 2) = kg(7, 7) = kg(8, 8) = 6.0 * Fx2 / (5.0 * L);
  kg(3, 3) = kg(9, 9) = Fx2 * Ip_A / L;
  kg(4, 4) = kg(5, 5) = kg(10, 10) = kg(11, 11) = 2.0 * Fx2 * L / 15.0;
  return kg;
}

Mat12 beam_local_axial_geometric_stiffness(const BeamSection& s, double L, const Vec12& f) {
  assert(L > 0.0 && s.A > 0.0);
  const double N = 0.5 * (f(6) - f(0));
  Mat12 kg = Mat12::Zero();
  // Axial and Wagner torsion terms: N/L [1 -1; -1 1] on u and N (Iy + Iz)/(A L) on rx.
  const double axial = N / L, torsion = N * (s.Iy + s.Iz) / (s.A * L);
  for (const auto& [i, k] : {std::pair{0, axial}, std::pair{3, torsion}}) {
    kg(i, i) = kg(i + 6, i + 6) = k;
    kg(i, i + 6) = kg(i + 6, i) = -k;
  }
  // Bending in one plane: translation t, rotation r, `sign` +1 for (v, rz), -1 for (w, ry)
  // (w' = -ry). Przemieniecki (1968) sec. 15.3 as coded in Frame3DD's geometric_K.
  const auto plane = [&](int t, int r, double sign, double phi) {
    const double D = (1.0 + phi) * (1.0 + phi);
    const double ktt = N / L * (1.2 + 2.0 * phi + phi * phi) / D;
    const double ktr = sign * N / (10.0 * D);
    const double krr = N * L * (2.0 / 15.0 + phi / 6.0 + phi * phi / 12.0) / D;
    const double krr2 = -N * L * (1.0 / 30.0 + phi / 6.0 + phi * phi / 12.0) / D;
    const int t2 = t + 6, r2 = r + 6;
    kg(t, t) = kg(t2, t2) = ktt;
    kg(t, t2) = kg(t2, t) = -ktt;
    kg(r, r) = kg(r2, r2) = krr;
    kg(r, r2) = kg(r2, r) = krr2;
    kg(t, r) = kg(r, t) = kg(t, r2) = kg(r2, t) = ktr;
    kg(t2, r) = kg(r, t2) = kg(t2, r2) = kg(r2, t2) = -ktr;
  };
  plane(1, 5, 1.0, s.phi_y(L));
  plane(2, 4, -1.0, s.phi_z(L));
  return kg;
}

}  // namespace beamfea
