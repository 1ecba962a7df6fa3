#include "io/ellipsoid_vtk.hpp"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace beamfea {

namespace {

// Mesh resolution: longitudes a multiple of 4 and latitudes even, so that the ends of all three
// semi-axes are mesh points (the file's extent along each axis is exactly the semi-axis).
constexpr int kLongitudes = 32;
constexpr int kLatitudes = 16;

vtkSmartPointer<vtkDoubleArray> field_data_array(const char* name, int components, std::initializer_list<double> values) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  for (double x : values) a->InsertNextValue(x);
  return a;
}

}  // namespace

double ellipsoid_scale(const ComplianceAxes& axes, double model_size) {
  const double largest = axes.semi_axes.maxCoeff();
  return largest > 0.0 ? kEllipsoidSizeFraction * model_size / largest : 0.0;
}

void write_compliance_ellipsoid(const std::string& path, const Vec3& centre, const ComplianceAxes& axes, double scale) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();  // a small semi-axis beside a large coordinate needs doubles
  vtkNew<vtkDoubleArray> compliance;
  compliance->SetName("compliance");
  // f: a unit force in the eigenbasis, at polar angle phi from axis 3 and longitude theta.
  const auto add = [&](double phi, double theta) {
    const Vec3 f(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), std::cos(phi));
    const Vec3 u = axes.axes * axes.semi_axes.cwiseProduct(f);  // C f
    const Vec3 x = centre + scale * u;
    points->InsertNextPoint(x.x(), x.y(), x.z());
    compliance->InsertNextValue(u.norm());
  };
  const double pi = std::numbers::pi;
  add(0.0, 0.0);  // point 0: the pole on +axis 3
  for (int i = 1; i < kLatitudes; ++i)
    for (int j = 0; j < kLongitudes; ++j) add(pi * i / kLatitudes, 2 * pi * j / kLongitudes);
  add(pi, 0.0);  // the pole on -axis 3
  const auto ring = [](int i, int j) -> vtkIdType { return 1 + (i - 1) * kLongitudes + (j % kLongitudes); };
  const vtkIdType south = 1 + (kLatitudes - 1) * kLongitudes;
  vtkNew<vtkCellArray> polys;
  for (int j = 0; j < kLongitudes; ++j) {
    const vtkIdType top[3] = {0, ring(1, j), ring(1, j + 1)};
    polys->InsertNextCell(3, top);
    for (int i = 1; i + 1 < kLatitudes; ++i) {
      const vtkIdType quad[4] = {ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)};
      polys->InsertNextCell(4, quad);
    }
    const vtkIdType bottom[3] = {ring(kLatitudes - 1, j), south, ring(kLatitudes - 1, j + 1)};
    polys->InsertNextCell(3, bottom);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(polys);
  poly->GetPointData()->AddArray(compliance);
  vtkFieldData* fd = poly->GetFieldData();
  fd->AddArray(field_data_array("scale", 1, {scale}));
  fd->AddArray(field_data_array("semi_axes", 1, {axes.semi_axes[0], axes.semi_axes[1], axes.semi_axes[2]}));
  const Mat3& a = axes.axes;
  fd->AddArray(field_data_array("axes", 3, {a(0, 0), a(1, 0), a(2, 0), a(0, 1), a(1, 1), a(2, 1), a(0, 2), a(1, 2), a(2, 2)}));
  fd->AddArray(field_data_array("centre", 3, {centre.x(), centre.y(), centre.z()}));

  write_atomic(path, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetFileName(tmp.c_str());
    w->SetInputData(poly);
    w->SetDataModeToAppended();
    w->EncodeAppendedDataOff();
    // LZ4 rather than VTK's default zlib: a few times faster to write (zlib took 40% of a
    // 400,000-DOF lattice's whole run) for files about a third larger; ParaView reads both.
    w->SetCompressorTypeToLZ4();
    if (w->Write() != 1) throw Error("cannot write VTK file '" + path + "'");
  });
}

}  // namespace beamfea
