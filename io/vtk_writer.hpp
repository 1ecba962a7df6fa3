#pragma once
// VTK XML output that ParaView opens as is: one .vtu per state, .pvd for series.
//
// Beams are drawn as `segments` line cells each (vtk_beam_segments), following the deformed shape (the cubic
// Hermite shape of the Euler-Bernoulli element by default, or a caller's shape function for
// large-rotation states). Rigid links are single line cells; joints are vertex cells.
// Point data: "displacement", "rotation" (rotation vector). Cell data: "section_forces"
// (N Vy Vz T My Mz at the cell's middle, local axes, N > 0 in tension), "N", "T", "My", "Mz",
// "kind" (0 beam, 1 rigid, 2 joint), "member_index", "element_index", and "id" (the user's id).
// Field data: any named scalars (load factor, step, stable flag...).
// With VtkFrame::section_forces, also point data "section_forces" and the diagrams as vectors
// across the member, "diagram_N", "diagram_Vy", "diagram_Mz" (along local y: bending in x-y),
// "diagram_Vz", "diagram_My" (along local z: bending in x-z), "diagram_T" (along local y): Warp By
// Vector on one of them with a small scale factor draws that diagram along every beam.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/beam.hpp"

namespace beamfea {

struct VtkFrame {
  std::vector<Vec3> displacement;      // per node
  std::vector<Vec3> rotation;          // per node (rotation vector)
  std::vector<Vec12> end_forces;       // per element, local, forces on the element at its ends (may be empty)
  std::map<std::string, double> field_data;
  std::map<std::string, std::vector<double>> node_scalars;  // extra point data at the model's nodes
  int segments = 0;  // line cells per beam; 0: vtk_beam_segments(model)
  // Optional: displacement of the beam axis of `element` at xi in [0, 1] (overrides the cubic).
  std::function<Vec3(int element, double xi)> shape;
  // Optional: section forces [N Vy Vz T My Mz] of a beam element at xi (member loads between the
  // nodes make them vary). When given, cell data is taken at each cell's middle and the point
  // data "section_forces" and the diagrams are written (see write_vtu).
  std::function<Vec6(int element, double xi)> section_forces;
};

// Line cells per beam when VtkFrame::segments is 0: 8, or fewer on a large model, so that its
// beams make at most kVtkBeamCellBudget cells (at least one each). Every beam's points are its
// own, each with about 30 values: eight segments of a million-member lattice would hold 5 GB in
// memory and 1.5 GB on disk, one segment 0.7 GB and 0.3 GB.
inline constexpr long kVtkBeamCellBudget = 1'000'000;
int vtk_beam_segments(const Model& model);

// Section forces (internal-force convention) at both ends from the element end forces:
// end 1: -F1, end 2: +F2, so that N > 0 is tension and moments follow the right-hand rule on the
// positive face.
Vec12 section_forces(const Vec12& end_forces);

void write_vtu(const std::string& path, const Model& model, const VtkFrame& frame);
// entries: (time value, file name relative to the .pvd)
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries);

}  // namespace beamfea
