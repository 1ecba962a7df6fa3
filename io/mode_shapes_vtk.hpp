#pragma once
// Output of a series of mode shapes (buckling, vibration): the results' node map of one mode, and
// the VTK series DIR/<id>_mode<k>.vtu and DIR/<id>.pvd with time = mode number, so that
// ParaView's time control steps through them.
#include <filesystem>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "io/analysis.hpp"

namespace beamfea {

// {"<node id>": {"displacement": [6 values of the raw mode u]}, ...} in the model's node order.
ojson mode_nodes_json(const Model& model, const Eigen::VectorXd& u);

// Writes the modes (raw displacement vectors), each normalised to a largest node translation of
// 1 and drawn at `scale` = 10 % of the model size; the unscaled normalised mode is point data
// mode_x, mode_y, mode_z; field data "mode", `value_name` = values[k], "scale". Returns the scale.
double write_mode_shapes(const Model& model, const std::filesystem::path& dir, const std::string& id,
                         const std::vector<Eigen::VectorXd>& modes, const std::string& value_name,
                         const Eigen::VectorXd& values);

}  // namespace beamfea
