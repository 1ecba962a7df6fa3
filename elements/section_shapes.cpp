#include "elements/section_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace beamfea {

namespace {

constexpr double pi = std::numbers::pi;

// A rectangle of width w (along y) and height h (along z) centred at (y, z), accumulated into the
// first and second moments about the origin.
struct Moments {
  double A = 0.0, Sy = 0.0, Sz = 0.0, Iyy = 0.0, Izz = 0.0, Iyz = 0.0;  // Iyy = int z^2, Izz = int y^2
  void add_rectangle(double w, double h, double y, double z) {
    const double a = w * h;
    A += a;
    Sy += a * z;
    Sz += a * y;
    Iyy += w * h * h * h / 12.0 + a * z * z;
    Izz += h * w * w * w / 12.0 + a * y * y;
    Iyz += a * y * z;
  }
  // The properties about the centroid.
  SectionProperties about_centroid() const {
    SectionProperties s;
    const double yc = Sz / A, zc = Sy / A;
    s.A = A;
    s.Iy = Iyy - A * zc * zc;
    s.Iz = Izz - A * yc * yc;
    s.Iyz = Iyz - A * yc * zc;
    return s;
  }
};

// The spandrel of a root radius r (the square r x r less the quarter disc centred at its far
// corner): area, distance c of its centroid from either leg through the near corner, and its
// second moment about its own centroidal axis parallel to a leg.
struct Fillet {
  double area, c, I;
};
Fillet fillet(double r) {
  const double a_sq = r * r, a_qd = pi * r * r / 4.0;
  const double e = 4.0 * r / (3.0 * pi);  // the quarter disc's centroid from its centre
  const double z_qd = r - e;              // ... from the leg through the near corner
  const double area = a_sq - a_qd;
  const double c = (a_sq * r / 2.0 - a_qd * z_qd) / area;
  const double I_leg = r * r * r * r / 3.0 - (pi * r * r * r * r / 16.0 - a_qd * e * e + a_qd * z_qd * z_qd);
  return {area, c, I_leg - area * c * c};
}

// Shear factor of plates of total area a_plates carrying the shear: k = A / A_v with A_v the
// plates' area times 5/6 (rectangles, k = 6/5 each).
double plate_shear_factor(double A, double a_plates) { return A / (a_plates * 5.0 / 6.0); }

// Every dimension named; "" when all are positive.
std::string need(bool ok, const char* message) { return ok ? std::string() : std::string(message); }

}  // namespace

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
  s.A = pi * r * r;
  s.Iy = s.Iz = pi * std::pow(r, 4) / 4.0;
  s.J = pi * std::pow(r, 4) / 2.0;
  s.ky = s.kz = 10.0 / 9.0;
  return s;
}

SectionProperties tube_section(double d, double t) {
  SectionProperties s;
  const double ro = 0.5 * d, ri = ro - t;
  s.A = pi * (ro * ro - ri * ri);
  s.Iy = s.Iz = pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4.0;
  s.J = 2.0 * s.Iy;
  s.ky = s.kz = 2.0;
  return s;
}

SectionProperties i_section(double h, double b, double tw, double tf, double r) {
  Moments m;
  const double hw = h - 2.0 * tf;  // the web between the flanges
  m.add_rectangle(b, tf, 0.0, 0.5 * (h - tf));
  m.add_rectangle(b, tf, 0.0, -0.5 * (h - tf));
  m.add_rectangle(tw, hw, 0.0, 0.0);
  SectionProperties s = m.about_centroid();
  // Saint-Venant's thin-walled open section: J = sum l t^3 / 3 over the three plates.
  s.J = (2.0 * b * tf * tf * tf + hw * tw * tw * tw) / 3.0;
  if (r > 0.0) {
    // Four fillets at the web-flange junctions, their centroids c inside the corners.
    const Fillet f = fillet(r);
    const double z = 0.5 * h - tf - f.c, y = 0.5 * tw + f.c;
    s.A += 4.0 * f.area;
    s.Iy += 4.0 * (f.I + f.area * z * z);
    s.Iz += 4.0 * (f.I + f.area * y * y);
    // El Darwish and Johnston (1965), the formula of the steel makers' tables (Roark's Formulas
    // for Stress and Strain, Table 10.7, I-section with fillets): two flanges with their end
    // correction, the web, and the two web-flange junctions of inscribed-circle diameter D.
    const double t1 = std::min(tw, tf), t2 = std::max(tw, tf);
    const double alpha = (0.15 + 0.1 * r / tf) * t1 / t2;
    const double D = ((tf + r) * (tf + r) + tw * (r + tw / 4.0)) / (2.0 * r + tf);
    s.J = 2.0 / 3.0 * b * std::pow(tf, 3) * (1.0 - 0.63 * tf / b) + hw * std::pow(tw, 3) / 3.0 + 2.0 * alpha * std::pow(D, 4) -
          0.420 * std::pow(tf, 4);
  }
  // Shear areas (Eurocode 3, EN 1993-1-1 6.2.6(3)(a)): along z the web, A - 2 b tf + (tw + 2 r) tf;
  // along y the two flanges (rectangles, 5/6 of their area).
  s.kz = s.A / (s.A - 2.0 * b * tf + (tw + 2.0 * r) * tf);
  s.ky = plate_shear_factor(s.A, 2.0 * b * tf);
  return s;
}

SectionProperties channel_section(double h, double b, double tw, double tf) {
  Moments m;
  const double hw = h - 2.0 * tf;
  m.add_rectangle(b, tf, 0.5 * b, 0.5 * (h - tf));
  m.add_rectangle(b, tf, 0.5 * b, -0.5 * (h - tf));
  m.add_rectangle(tw, hw, 0.5 * tw, 0.0);
  SectionProperties s = m.about_centroid();
  s.Iyz = 0.0;  // symmetric about y
  s.J = (2.0 * b * tf * tf * tf + hw * tw * tw * tw) / 3.0;
  s.kz = s.A / ((h - tf) * tw);  // EN 1993-1-1 6.2.6(3)(b) with r = 0: A - 2 b tf + tw tf
  s.ky = plate_shear_factor(s.A, 2.0 * b * tf);
  return s;
}

SectionProperties tee_section(double h, double b, double tw, double tf) {
  Moments m;
  const double hs = h - tf;  // the stem below the flange
  m.add_rectangle(b, tf, 0.0, h - 0.5 * tf);
  m.add_rectangle(tw, hs, 0.0, 0.5 * hs);
  SectionProperties s = m.about_centroid();
  s.Iyz = 0.0;  // symmetric about z
  s.J = (b * tf * tf * tf + hs * tw * tw * tw) / 3.0;
  s.kz = plate_shear_factor(s.A, h * tw);  // the stem, through the flange
  s.ky = plate_shear_factor(s.A, b * tf);
  return s;
}

SectionProperties angle_section(double h, double b, double t) {
  Moments m;
  m.add_rectangle(t, h, 0.5 * t, 0.5 * h);                  // the leg along z, with the heel
  m.add_rectangle(b - t, t, t + 0.5 * (b - t), 0.5 * t);    // the leg along y, beyond it
  SectionProperties s = m.about_centroid();
  s.J = (h + b - t) * t * t * t / 3.0;
  s.kz = plate_shear_factor(s.A, h * t);
  s.ky = plate_shear_factor(s.A, b * t);
  return s;
}

SectionProperties box_section(double h, double b, double t) {
  SectionProperties s;
  const double bi = b - 2.0 * t, hi = h - 2.0 * t;
  s.A = b * h - bi * hi;
  s.Iy = (b * h * h * h - bi * hi * hi * hi) / 12.0;
  s.Iz = (h * b * b * b - hi * bi * bi * bi) / 12.0;
  // Bredt: J = 4 A_m^2 t / contour, A_m and the contour of the wall's centre line.
  const double bm = b - t, hm = h - t;
  s.J = 4.0 * bm * bm * hm * hm * t / (2.0 * (bm + hm));
  // Shear areas of a rectangular hollow section (EN 1993-1-1 6.2.6(3)(c)): A h/(b + h) along z
  // (the webs), A b/(b + h) along y.
  s.kz = (b + h) / h;
  s.ky = (b + h) / b;
  return s;
}

PrincipalMoments principal_moments(double Iy, double Iz, double Iyz) {
  const double mean = 0.5 * (Iy + Iz), half = 0.5 * (Iy - Iz);
  const double radius = std::hypot(half, Iyz);
  // The axis at angle a from y has I(a) = mean + half cos 2a - Iyz sin 2a (I = int z'^2 dA).
  return {mean + radius, mean - radius, 0.5 * std::atan2(-Iyz, half)};
}

const std::vector<SectionShape>& section_shapes() {
  using D = const ShapeDimensions&;
  static const std::vector<SectionShape> shapes{
      {"rectangle", {"b", "h"}, {}, "solid rectangle, b along local y, h along local z",
       "A = b h; Iz = h b^3/12; Iy = b h^3/12; J = a c^3 [1/3 - 0.21 (c/a)(1 - (c/a)^4/12)], a = max(b, h), c = min(b, h) "
       "(Roark, Table 10.7 case 4); k = 6/5",
       [](D d) { return rectangle_section(d[0], d[1]); }, [](D) { return std::string(); }},
      {"circle", {}, {"d", "r"}, "solid circle, diameter d or radius r",
       "A = pi r^2; Iy = Iz = pi r^4/4; J = pi r^4/2 (exact); k = 10/9",
       [](D d) { return circle_section(d[0] > 0.0 ? 0.5 * d[0] : d[1]); },
       [](D d) { return need((d[0] > 0.0) != (d[1] > 0.0), "d: give the diameter d or the radius r (one of them)"); }},
      {"tube", {"d", "t"}, {}, "circular tube, outer diameter d, wall t",
       "A = pi (ro^2 - ri^2); Iy = Iz = pi (ro^4 - ri^4)/4; J = 2 Iy; k = 2 (thin-walled tube, Cowper 1966)",
       [](D d) { return tube_section(d[0], d[1]); }, [](D d) { return need(d[1] < 0.5 * d[0], "t: the wall must be thinner than d/2"); }},
      {"i", {"h", "b", "tw", "tf"}, {"r"},
       "doubly symmetric I or H: depth h along local z, flange width b along local y, web tw, flanges tf, root radius r (optional)",
       "A, Iy, Iz of the three plates (plus four fillets (1 - pi/4) r^2 when r > 0); J = (2 b tf^3 + (h - 2 tf) tw^3)/3 "
       "(thin-walled), with r > 0 El Darwish and Johnston's formula (Roark, Table 10.7); kz = A / (A - 2 b tf + (tw + 2 r) tf) "
       "(EN 1993-1-1 6.2.6), ky = A / (5/6 2 b tf)",
       [](D d) { return i_section(d[0], d[1], d[2], d[3], d[4]); },
       [](D d) {
         if (!(2.0 * d[3] < d[0])) return std::string("tf: 2 tf must be below h");
         if (!(d[2] < d[1])) return std::string("tw: tw must be below b");
         if (!(d[2] + 2.0 * d[4] <= d[1] && 2.0 * (d[3] + d[4]) <= d[0])) return std::string("r: the root radii must fit between web and flange tips");
         return std::string();
       }},
      {"channel", {"h", "b", "tw", "tf"}, {}, "channel: web h along local z, flanges b along local y, web tw, flanges tf",
       "A, Iy, Iz of the three plates about the centroid; J = (2 b tf^3 + (h - 2 tf) tw^3)/3 (thin-walled); kz = A / ((h - tf) tw), "
       "ky = A / (5/6 2 b tf); the shear centre (behind the web) is not modelled",
       [](D d) { return channel_section(d[0], d[1], d[2], d[3]); },
       [](D d) {
         if (!(2.0 * d[3] < d[0])) return std::string("tf: 2 tf must be below h");
         return need(d[2] < d[1], "tw: tw must be below b");
       }},
      {"tee", {"h", "b", "tw", "tf"}, {}, "tee: flange b along local y at the top (+z), total depth h along local z, stem tw, flange tf",
       "A, Iy, Iz of the two plates about the centroid; J = (b tf^3 + (h - tf) tw^3)/3 (thin-walled); kz = A / (5/6 h tw), "
       "ky = A / (5/6 b tf); the shear centre (at the flange) is not modelled",
       [](D d) { return tee_section(d[0], d[1], d[2], d[3]); },
       [](D d) {
         if (!(d[3] < d[0])) return std::string("tf: tf must be below h");
         return need(d[2] < d[1], "tw: tw must be below b");
       }},
      {"angle", {"h", "b", "t"}, {}, "angle: legs h along local z and b along local y, thickness t",
       "A, Iy, Iz, Iyz of the two legs about the centroid (axes parallel to the legs); J = (h + b - t) t^3/3 (thin-walled); "
       "kz = A / (5/6 h t), ky = A / (5/6 b t); the element neglects Iyz (listed with the principal values)",
       [](D d) { return angle_section(d[0], d[1], d[2]); },
       [](D d) { return need(d[2] < std::min(d[0], d[1]), "t: t must be below b and h"); }},
      {"box", {"h", "b", "t"}, {}, "rectangular hollow section: outer h along local z and b along local y, wall t",
       "A, Iy, Iz of the outer less the inner rectangle; J = 2 t (b - t)^2 (h - t)^2 / (b + h - 2 t) (Bredt, centre line); "
       "kz = (b + h)/h, ky = (b + h)/b (EN 1993-1-1 6.2.6)",
       [](D d) { return box_section(d[0], d[1], d[2]); },
       [](D d) { return need(2.0 * d[2] < std::min(d[0], d[1]), "t: 2 t must be below b and h"); }},
  };
  return shapes;
}

const SectionShape* find_section_shape(std::string_view name) {
  for (const auto& s : section_shapes())
    if (s.name == name) return &s;
  return nullptr;
}

std::string section_shape_names() {
  std::string out;
  for (const auto& s : section_shapes()) out.append(out.empty() ? "" : ", ").append(s.name);
  return out;
}

std::string section_shape_dimensions(const SectionShape& shape) {
  std::string takes;
  for (const auto& k : shape.dimensions) takes.append(takes.empty() ? "" : ", ").append(k);
  for (const auto& k : shape.optional) takes.append(takes.empty() ? "" : ", ").append(k).append(" (optional)");
  return takes;
}

SectionProperties section_properties(std::string_view name, const std::vector<std::pair<std::string, double>>& dimensions) {
  const SectionShape* shape = find_section_shape(name);
  if (!shape) throw std::invalid_argument("unknown shape '" + std::string(name) + "' (expected " + section_shape_names() + ")");
  const std::string takes = section_shape_dimensions(*shape);
  ShapeDimensions d{};
  std::vector<char> given(shape->dimensions.size() + shape->optional.size(), 0);
  for (const auto& [key, value] : dimensions) {
    std::size_t i = 0;
    while (i < given.size() && key != (i < shape->dimensions.size() ? shape->dimensions[i] : shape->optional[i - shape->dimensions.size()])) ++i;
    if (i == given.size()) throw std::invalid_argument("shape '" + std::string(name) + "' takes " + takes + ", not '" + key + "'");
    if (given[i]) throw std::invalid_argument(key + ": given twice");
    if (!(std::isfinite(value) && value > 0.0)) throw std::invalid_argument(key + ": must be a positive number");
    given[i] = 1;
    d[i] = value;
  }
  for (std::size_t i = 0; i < shape->dimensions.size(); ++i)
    if (!given[i]) throw std::invalid_argument("shape '" + std::string(name) + "' needs " + std::string(shape->dimensions[i]) + " (it takes " + takes + ")");
  if (const std::string bad = shape->check(d); !bad.empty()) throw std::invalid_argument(bad);
  return shape->compute(d);
}

}  // namespace beamfea
