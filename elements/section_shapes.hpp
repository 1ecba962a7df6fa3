#pragma once
// Section properties of common shapes (docs/input-format.md, "sections"; `beamfea sections`).
//
// Local axes as for the beam (elements/beam.hpp): Iz governs bending in the local x-y plane,
// Iy bending in the local x-z plane. For every shape `b` is measured along local y and `h` along
// local z (the depth), and the properties are about axes through the centroid, parallel to y and z.
// ky, kz are the shear correction factors (shear areas A/ky along y, A/kz along z) of a Timoshenko
// beam.
//
// Thin-walled shapes (i, channel, tee, angle, box) are assemblies of rectangular plates: A, Iy, Iz
// of the plates exactly (no overlap), J by the thin-walled formulas (open sections: Saint-Venant's
// J = sum l t^3 / 3 over the plates; the closed box: Bredt's J = 4 A_m^2 / (contour / t)). Rolled
// sections have root radii that the plates leave out: 3-4 % of A and I and about 30 % of J for an
// IPE 300; the `i` shape takes the root radius `r` to add them (fillets of area (1 - pi/4) r^2 in
// A and I; J by El Darwish and Johnston's formula). The shear centre of a channel, tee or angle is
// not at the centroid, and an angle's y and z are not its principal axes (product of inertia Iyz):
// the beam element couples neither; SectionProperties reports Iyz and the principal values.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace beamfea {

struct SectionProperties {
  double A = 0.0, Iy = 0.0, Iz = 0.0, J = 0.0, ky = 0.0, kz = 0.0;
  // Product of inertia about the centroidal y and z, integral of y z dA (nonzero for an angle);
  // the element neglects it.
  double Iyz = 0.0;
};

// Solid rectangle, b along local y, h along local z. J is Saint-Venant's torsion constant
// (Roark's Formulas for Stress and Strain, 7th ed., Table 10.7 case 4); k = 6/5.
SectionProperties rectangle_section(double b, double h);

// Solid circle of radius r; J = polar moment pi r^4 / 2 (exact for a circle); k = 10/9.
SectionProperties circle_section(double r);

// Thin or thick circular tube of outer diameter d and wall thickness t < d/2; J = 2 I; k = 2
// (thin-walled tube, Cowper 1966).
SectionProperties tube_section(double d, double t);

// Doubly symmetric I or H: depth h (along z), flange width b (along y), web thickness tw, flange
// thickness tf, root radius r (0: plates only).
SectionProperties i_section(double h, double b, double tw, double tf, double r = 0.0);
// Channel: web of height h along z (at the back, y < 0 of the centroid), flanges b along +y.
SectionProperties channel_section(double h, double b, double tw, double tf);
// Tee: flange b x tf at the top (+z), stem of thickness tw, total depth h.
SectionProperties tee_section(double h, double b, double tw, double tf);
// Angle: legs h along z and b along y, thickness t, the heel at the corner of -y and -z.
SectionProperties angle_section(double h, double b, double t);
// Rectangular hollow (box): outer h along z and b along y, wall t.
SectionProperties box_section(double h, double b, double t);

// Principal second moments (I1 >= I2) of (Iy, Iz, Iyz) and the angle (radians, from local y
// towards local z) of the axis of I1.
struct PrincipalMoments {
  double I1 = 0.0, I2 = 0.0, angle = 0.0;
};
PrincipalMoments principal_moments(double Iy, double Iz, double Iyz);

// A shape's dimensions, required then optional, in the order of SectionShape's lists.
inline constexpr std::size_t kMaxShapeDimensions = 6;
using ShapeDimensions = std::array<double, kMaxShapeDimensions>;

// The shapes a section's "shape" names, for the reader and `beamfea sections`.
struct SectionShape {
  std::string_view name;
  std::vector<std::string_view> dimensions;  // required, in the order `compute` takes them
  std::vector<std::string_view> optional;    // optional dimensions (0 when not given)
  std::string_view description;              // one line: what the dimensions are
  std::string_view formulas;                 // how A, I, J, k are computed, with the sources
  // Properties of dimensions (required then optional, in their order); throws nothing.
  SectionProperties (*compute)(const ShapeDimensions& dimensions);
  // "" when the dimensions (all > 0, or >= 0 where optional) make the shape; else what is wrong,
  // naming the dimension (e.g. "tf: 2 tf must be below h").
  std::string (*check)(const ShapeDimensions& dimensions);
};
const std::vector<SectionShape>& section_shapes();
const SectionShape* find_section_shape(std::string_view name);
// "rectangle, circle, tube, i, channel, tee, angle, box"
std::string section_shape_names();
// The dimensions a shape takes, for messages: "h, b, tw, tf, r (optional)".
std::string section_shape_dimensions(const SectionShape& shape);

// The properties of shape `name` of the named dimensions (the command line's and Python's way in;
// the model reader checks the same with JSON pointers). Throws std::invalid_argument naming the
// shape or the dimension at fault: an unknown shape, a missing, unknown, repeated or non-positive
// dimension, dimensions that do not make the shape.
SectionProperties section_properties(std::string_view name, const std::vector<std::pair<std::string, double>>& dimensions);

}  // namespace beamfea
