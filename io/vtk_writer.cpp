#include "io/vtk_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <sstream>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace beamfea {

Vec12 section_forces(const Vec12& f) {
  Vec12 s;
  s.head<6>() = -f.head<6>();
  s.tail<6>() = f.tail<6>();
  return s;
}

void write_vtu(const std::string& path, const Model& model, const VtkFrame& frame) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkDoubleArray> disp, rot, secf, N, T, My, Mz;
  disp->SetName("displacement");
  disp->SetNumberOfComponents(3);
  rot->SetName("rotation");
  rot->SetNumberOfComponents(3);
  secf->SetName("section_forces");
  secf->SetNumberOfComponents(6);
  const char* comp_names[6] = {"N", "Vy", "Vz", "T", "My", "Mz"};
  for (int k = 0; k < 6; ++k) secf->SetComponentName(k, comp_names[k]);
  N->SetName("N");
  T->SetName("T");
  My->SetName("My");
  Mz->SetName("Mz");
  vtkNew<vtkIntArray> kind, member_index, element_index;
  kind->SetName("kind");
  member_index->SetName("member_index");
  element_index->SetName("element_index");
  vtkNew<vtkStringArray> ids;
  ids->SetName("id");
  std::vector<int> cell_types;
  // Diagrams (point data; only with frame.section_forces).
  const bool diagrams = static_cast<bool>(frame.section_forces);
  const char* diagram_names[6] = {"diagram_N", "diagram_Vy", "diagram_Vz", "diagram_T", "diagram_My", "diagram_Mz"};
  const int diagram_axis[6] = {1, 1, 2, 1, 2, 1};  // local axis across which each is drawn
  vtkNew<vtkDoubleArray> psecf;
  psecf->SetName("section_forces");
  psecf->SetNumberOfComponents(6);
  for (int k = 0; k < 6; ++k) psecf->SetComponentName(k, comp_names[k]);
  std::vector<vtkSmartPointer<vtkDoubleArray>> diag;
  for (int k = 0; k < 6; ++k) {
    diag.push_back(vtkSmartPointer<vtkDoubleArray>::New());
    diag.back()->SetName(diagram_names[k]);
    diag.back()->SetNumberOfComponents(3);
  }
  // Point values for points that are not on a beam (rigid links, joints).
  auto add_point_forces = [&](const Vec6& f, const Mat3* R) {
    if (!diagrams) return;
    psecf->InsertNextTuple(f.data());
    for (int k = 0; k < 6; ++k) {
      const Vec3 v = R ? Vec3(f[k] * R->row(diagram_axis[k]).transpose()) : Vec3::Zero();
      diag[k]->InsertNextTuple3(v.x(), v.y(), v.z());
    }
  };
  std::map<std::string, vtkSmartPointer<vtkDoubleArray>> extra;
  for (const auto& [name, values] : frame.node_scalars) {
    auto a = vtkSmartPointer<vtkDoubleArray>::New();
    a->SetName(name.c_str());
    extra[name] = a;
  }

  auto add_point = [&](const Vec3& x, const Vec3& u, const Vec3& r, int node) {
    const vtkIdType id = points->InsertNextPoint(x.x(), x.y(), x.z());
    disp->InsertNextTuple3(u.x(), u.y(), u.z());
    rot->InsertNextTuple3(r.x(), r.y(), r.z());
    for (const auto& [name, values] : frame.node_scalars)
      extra[name]->InsertNextValue(node >= 0 && node < static_cast<int>(values.size()) ? values[node] : 0.0);
    return id;
  };
  const bool have_forces = frame.end_forces.size() == model.elements.size();
  auto add_cell_data = [&](int k, int member, int element, const std::string& id, const Vec6& s) {
    kind->InsertNextValue(k);
    member_index->InsertNextValue(member);
    element_index->InsertNextValue(element);
    ids->InsertNextValue(id);
    secf->InsertNextTuple(s.data());
    N->InsertNextValue(s[0]);
    T->InsertNextValue(s[3]);
    My->InsertNextValue(s[4]);
    Mz->InsertNextValue(s[5]);
  };

  const int segs = std::max(1, frame.segments);
  for (int e = 0; e < static_cast<int>(model.elements.size()); ++e) {
    const auto& el = model.elements[e];
    const int a = el.nodes[0], b = el.nodes[1];
    const Vec3 Xa = model.nodes[a].x, Xb = model.nodes[b].x;
    const std::string id = el.member >= 0 ? model.members[el.member].id : el.id;
    const Vec12 sf = have_forces ? section_forces(frame.end_forces[e]) : Vec12::Zero();
    const int n = el.type == MemberType::Beam ? segs : 1;
    std::optional<Mat3> R;
    Vec12 ue;
    if (el.type == MemberType::Beam && !frame.shape) {
      R = beam_local_axes(Xa, Xb, el.orientation);
      ue << frame.displacement[a], frame.rotation[a], frame.displacement[b], frame.rotation[b];
    }
    vtkIdType prev = -1;
    for (int k = 0; k <= n; ++k) {
      const double xi = static_cast<double>(k) / n;
      const Vec3 X = (1 - xi) * Xa + xi * Xb;
      Vec3 u;
      if (k == 0) u = frame.displacement[a];
      else if (k == n) u = frame.displacement[b];
      else if (frame.shape) u = frame.shape(e, xi);
      else if (R) u = beam_displacement_at(*R, (Xb - Xa).norm(), ue, xi);
      else u = (1 - xi) * frame.displacement[a] + xi * frame.displacement[b];
      const Vec3 r = (1 - xi) * frame.rotation[a] + xi * frame.rotation[b];
      const vtkIdType id_pt = add_point(X, u, r, k == 0 ? a : (k == n ? b : -1));
      const bool beam_forces = diagrams && el.type == MemberType::Beam;
      if (beam_forces) {
        const Mat3 Rl = beam_local_axes(Xa, Xb, el.orientation);
        add_point_forces(frame.section_forces(e, xi), &Rl);
      } else {
        add_point_forces(Vec6::Zero(), nullptr);
      }
      if (k > 0) {
        const vtkIdType line[2] = {prev, id_pt};
        cells->InsertNextCell(2, line);
        cell_types.push_back(3);  // VTK_LINE
        const double xm = (k - 0.5) / n;
        const Vec6 s = beam_forces ? frame.section_forces(e, xm) : Vec6((1 - xm) * sf.head<6>() + xm * sf.tail<6>());
        add_cell_data(el.type == MemberType::Beam ? 0 : 1, el.member, e, id, s);
      }
      prev = id_pt;
    }
  }
  for (const auto& j : model.joints) {
    const int a = j.nodes[1];
    const vtkIdType id_pt = add_point(model.nodes[a].x, frame.displacement[a], frame.rotation[a], a);
    add_point_forces(Vec6::Zero(), nullptr);
    cells->InsertNextCell(1, &id_pt);
    cell_types.push_back(1);  // VTK_VERTEX
    add_cell_data(2, -1, -1, j.id, Vec6::Zero());
  }

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(cell_types.data(), cells);
  grid->GetPointData()->AddArray(disp);
  grid->GetPointData()->SetVectors(disp);
  grid->GetPointData()->AddArray(rot);
  for (auto& [name, a] : extra) grid->GetPointData()->AddArray(a);
  if (diagrams) {
    grid->GetPointData()->AddArray(psecf);
    for (auto& d : diag) grid->GetPointData()->AddArray(d);
  }
  grid->GetCellData()->AddArray(secf);
  grid->GetCellData()->AddArray(N);
  grid->GetCellData()->AddArray(T);
  grid->GetCellData()->AddArray(My);
  grid->GetCellData()->AddArray(Mz);
  grid->GetCellData()->AddArray(kind);
  grid->GetCellData()->AddArray(member_index);
  grid->GetCellData()->AddArray(element_index);
  grid->GetCellData()->AddArray(ids);
  for (const auto& [name, value] : frame.field_data) {
    vtkNew<vtkDoubleArray> f;
    f->SetName(name.c_str());
    f->InsertNextValue(value);
    grid->GetFieldData()->AddArray(f);
  }

  write_atomic(path, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetFileName(tmp.c_str());
    w->SetInputData(grid);
    w->SetDataModeToAppended();
    w->EncodeAppendedDataOff();
    if (w->Write() != 1) throw Error("cannot write VTK file '" + path + "'");
  });
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries) {
  std::ostringstream s;
  s.precision(17);
  s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n";
  for (const auto& [t, file] : entries)
    s << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  write_text_atomic(path, s.str());
}

}  // namespace beamfea
