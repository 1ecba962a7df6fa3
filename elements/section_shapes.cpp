#include "elements/section_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace beamfea {

SectionProperties rectangle_section(double b, double h) {
  SectionProperties s;
  s.A = b * h;
  s.Iz = h * b * b * b / 12.0;
  s.Iy = b * h * h * h / 12.0;
  // Roark, Table 10.7 case 4: J = a c^3 [1/3 - 0.21 (c/a) (1 - (c/a)^4 / 12)], a >= c.
  const double a = std::max(b, h), c = std::min(b, h), r = c / a;
  s.J = a * c * c * c * (1.0 / 3.0 - 0.21 * r * (1.0 - std::pow(r, 4) / 12.0));
  s.ky = s.kz = 6.0 / 5.0;
  return s;
}

SectionProperties circle_section(double r) {
  SectionProperties s;
  s.A = std::numbers::pi * r * r;
  s.Iy = s.Iz = std::numbers::pi * std::pow(r, 4) / 4.0;
  s.J = std::numbers::pi * std::pow(r, 4) / 2.0;
  s.ky = s.kz = 10.0 / 9.0;
  return s;
}

SectionProperties tube_section(double d, double t) {
  SectionProperties s;
  const double ro = 0.5 * d, ri = ro - t;
  s.A = std::numbers::pi * (ro * ro - ri * ri);
  s.Iy = s.Iz = std::numbers::pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4.0;
  s.J = 2.0 * s.Iy;
  s.ky = s.kz = 2.0;
  return s;
}

}  // namespace beamfea
