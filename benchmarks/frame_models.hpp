#pragma once
// The generated frames of bench_frame_solve, shared with bench_modal_solve: n x n bays of 6 m,
// storeys of 3.5 m, HEB 300-like columns and IPE 400-like beams, bases clamped, every floor node
// loaded.
#include <cstdlib>
#include <string>

#include "core/model.hpp"

namespace beamfea::bench {

struct Dims {
  int nx = 1, ny = 1, nz = 1;
  long nodes() const { return long(nx + 1) * (ny + 1) * (nz + 1); }
  long elements() const { return long(nz) * (long(nx + 1) * (ny + 1) + long(nx) * (ny + 1) + long(nx + 1) * ny); }
};

// The nx = ny (or ny = nx + 1) frame whose element count is closest to `target`; nz = nx
// (give or take one) for a cube, or nz = stories.
inline Dims choose_dims(long target, int stories = 0) {
  Dims best;
  long best_err = -1;
  for (int nx = 1; nx <= 4000; ++nx)
    for (int dy = 0; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        Dims d{nx, nx + dy, stories > 0 ? stories : nx + dz};
        if (d.nz < 1 || (stories > 0 && dz != 0)) continue;
        const long err = std::labs(d.elements() - target);
        if (best_err < 0 || err < best_err) {
          best_err = err;
          best = d;
        }
      }
  return best;
}

inline constexpr double kBayX = 6.0, kBayY = 6.0, kStorey = 3.5;
inline const beamfea::Vec3 kNodeForce(1e3, 0.5e3, -10e3);

inline beamfea::Model make_frame(const Dims& d, double density = 0.0) {
  using namespace beamfea;
  Model m;
  m.materials.push_back({"steel", 2.1e11, 8.1e10, density});
  // Column: HEB 300-like; beam: IPE 400-like (m^2, m^4).
  m.sections.push_back({"column", 1.49e-2, 2.517e-4, 0.8563e-4, 1.85e-6, 0.0, 0.0});
  m.sections.push_back({"beam", 8.45e-3, 2.313e-4, 1.318e-5, 5.1e-7, 0.0, 0.0});
  auto node = [&](int i, int j, int k) { return i + (d.nx + 1) * (j + (d.ny + 1) * k); };
  m.nodes.reserve(d.nodes());
  for (int k = 0; k <= d.nz; ++k)
    for (int j = 0; j <= d.ny; ++j)
      for (int i = 0; i <= d.nx; ++i)
        m.nodes.push_back({std::to_string(m.nodes.size()), Vec3(kBayX * i, kBayY * j, kStorey * k), -1});
  m.elements.reserve(d.elements());
  auto element = [&](int a, int b, int section, const Vec3& orientation) {
    Element e;
    e.id = std::to_string(m.elements.size());
    e.type = MemberType::Beam;
    e.nodes = {a, b};
    e.material = 0;
    e.section = section;
    e.orientation = orientation;
    m.elements.push_back(std::move(e));
  };
  // Storey by storey: the columns below a floor, then its beams (a natural input order).
  for (int k = 1; k <= d.nz; ++k) {
    for (int j = 0; j <= d.ny; ++j)
      for (int i = 0; i <= d.nx; ++i) element(node(i, j, k - 1), node(i, j, k), 0, Vec3::UnitX());
    for (int j = 0; j <= d.ny; ++j)
      for (int i = 0; i < d.nx; ++i) element(node(i, j, k), node(i + 1, j, k), 1, Vec3::UnitZ());
    for (int j = 0; j < d.ny; ++j)
      for (int i = 0; i <= d.nx; ++i) element(node(i, j, k), node(i, j + 1, k), 1, Vec3::UnitZ());
  }
  for (int j = 0; j <= d.ny; ++j)
    for (int i = 0; i <= d.nx; ++i) {
      Support s;
      s.node = node(i, j, 0);
      s.fixed.fill(true);
      m.supports.push_back(s);
    }
  for (int n = (d.nx + 1) * (d.ny + 1); n < static_cast<int>(m.nodes.size()); ++n)
    m.default_case.nodal.push_back({n, kNodeForce, Vec3::Zero()});
  return m;
}

}  // namespace beamfea::bench
