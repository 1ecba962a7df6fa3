#pragma once
// What a valid model may still hold by mistake: things defined and never used, loads that no
// structure carries. Nothing here is an error (the model runs as given); each finding is one line
// for the run's warnings (io/run.hpp: printed by the program as "beamfea: warning: ...", raised by
// Python as beamfea.BeamfeaWarning, listed in results.json's "warnings").
#include <string>
#include <vector>

#include "core/model.hpp"

namespace beamfea {

// At most this many ids are named in one warning ("... and 12 more"): a generated model with
// thousands of unused nodes gets one readable line, not thousands.
inline constexpr std::size_t kMaxIdsPerWarning = 8;

// The model's warnings, in this order:
//   materials and sections defined and never used by an element;
//   nodes connected to nothing (no element, joint, tie or linear constraint with another node);
//   per load case ("default" first), nodal loads on a node whose every DOF is supported or
//   prescribed (the load goes straight into the reactions; no structure carries it).
std::vector<std::string> model_warnings(const Model& m);

}  // namespace beamfea
