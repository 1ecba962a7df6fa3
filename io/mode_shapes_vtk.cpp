#include "io/mode_shapes_vtk.hpp"

#include <fmt/format.h>

#include "io/vtk_writer.hpp"
#include "solvers/buckling.hpp"

namespace beamfea {

ojson mode_nodes_json(const Model& model, const Eigen::VectorXd& u) {
  ojson nodes = object_with_capacity(model.nodes.size());
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    append_new_key(nodes, model.nodes[n].id, ojson{{"displacement", to_json(Vec6(u.segment<6>(6 * static_cast<Eigen::Index>(n))))}});
  return nodes;
}

double write_mode_shapes(const Model& model, const std::filesystem::path& dir, const std::string& id,
                         const std::vector<Eigen::VectorXd>& modes, const std::string& value_name,
                         const Eigen::VectorXd& values) {
  // Modes drawn at an amplitude of 10 % of the model size; ParaView steps through them as times
  // (Warp By Vector on "displacement" with a varying factor animates one mode).
  const double scale = 0.1 * model.length_scale();
  std::vector<std::pair<double, std::string>> entries;
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const Eigen::VectorXd u = normalise_mode(model, modes[k]);
    VtkFrame f;
    std::vector<double> mx, my, mz;
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      const Vec3 d = u.segment<3>(6 * static_cast<Eigen::Index>(n));
      f.displacement.push_back(scale * d);
      f.rotation.push_back(scale * Vec3(u.segment<3>(6 * static_cast<Eigen::Index>(n) + 3)));
      mx.push_back(d.x());
      my.push_back(d.y());
      mz.push_back(d.z());
    }
    f.node_scalars["mode_x"] = mx;
    f.node_scalars["mode_y"] = my;
    f.node_scalars["mode_z"] = mz;
    f.field_data["mode"] = static_cast<double>(k + 1);
    f.field_data[value_name] = values[static_cast<Eigen::Index>(k)];
    f.field_data["scale"] = scale;
    const std::string file = fmt::format("{}_mode{}.vtu", id, k + 1);
    write_vtu((dir / file).string(), model, f);
    entries.emplace_back(static_cast<double>(k + 1), file);
  }
  write_pvd((dir / (id + ".pvd")).string(), entries);
  return scale;
}

}  // namespace beamfea
