#pragma once
// The translational compliance ellipsoid of a node as VTK PolyData (DIR/<id>_ellipsoid.vtp): the
// surface { x_node + scale C_tt f : |f| = 1 }, semi-axes scale * lambda_i(C_tt) along the
// eigenvectors (solvers/stiffness_indices.hpp, compliance_axes), drawn at the node's place in the
// model (the posed geometry when the model is posed).
#include <string>

#include "core/model.hpp"
#include "solvers/stiffness_indices.hpp"

namespace beamfea {

// The largest semi-axis is drawn at this fraction of the model size (Model::length_scale, the
// bounding-box diagonal), as the mode shapes are.
inline constexpr double kEllipsoidSizeFraction = 0.1;

// The drawing scale (force units: length per compliance) that makes the largest semi-axis
// kEllipsoidSizeFraction * model_size; 0 when the node cannot move (every semi-axis zero: the
// ellipsoid is a point).
double ellipsoid_scale(const ComplianceAxes& axes, double model_size);

// Writes the ellipsoid atomically: a latitude-longitude mesh of triangles and quads whose poles
// and equator points lie on the ends of the semi-axes; field data "scale", "semi_axes" (the
// compliance eigenvalues, unscaled, descending), "axes" (their unit directions, one 3-tuple each)
// and "centre"; point data "compliance" (|C f| of the unit force f drawn there).
void write_compliance_ellipsoid(const std::string& path, const Vec3& centre, const ComplianceAxes& axes, double scale);

}  // namespace beamfea
