#include "elements/geometric_stiffness.hpp"

#include <cassert>

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

}  // namespace beamfea
