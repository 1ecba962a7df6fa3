#pragma once
// Section properties of common solid shapes (docs/input-format.md, "sections").
//
// Local axes as for the beam (elements/beam.hpp): Iz governs bending in the local x-y plane,
// Iy bending in the local x-z plane. Dimensions must be positive (the caller checks).
// ky, kz are the shear correction factors of the shape (used by the virtual-force shear term
// only; the beams are Euler-Bernoulli).
namespace beamfea {

struct SectionProperties {
  double A = 0.0, Iy = 0.0, Iz = 0.0, J = 0.0, ky = 0.0, kz = 0.0;
};

// Solid rectangle, b along local y, h along local z. J is Saint-Venant's torsion constant
// (Roark's Formulas for Stress and Strain, 7th ed., Table 10.7 case 4); k = 6/5.
SectionProperties rectangle_section(double b, double h);

// Solid circle of radius r; J = polar moment pi r^4 / 2 (exact for a circle); k = 10/9.
SectionProperties circle_section(double r);

// Thin or thick circular tube of outer diameter d and wall thickness t < d/2; J = 2 I; k = 2
// (thin-walled tube, Cowper 1966).
SectionProperties tube_section(double d, double t);

}  // namespace beamfea
