#pragma once
// The spec of the "actuator_allocation" analysis (io/analysis_actuator_allocation.cpp, which runs
// it): reading and validating it against the model. docs/analyses/actuator-allocation.md.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/model.hpp"
#include "io/json_pointer.hpp"
#include "solvers/actuator_allocation.hpp"

namespace beamfea::allocation_spec {

// The unloaded components (results' "components", the stiffness CSV), then the loaded ones of a
// load case (rank_by only; results' "loaded_stiffness.components").
inline constexpr const char* kComponents[] = {"actuated",        "structural",      "total_eq19",
                                              "total",           "total_fea",       "loaded_actuated",
                                              "loaded_structural", "loaded_total"};
inline constexpr int kUnloadedComponents = 5;
inline constexpr int kComponentCount = 8;

struct Pose {
  std::string id;
  std::vector<std::pair<int, Vec3>> nodes;
};

struct Spec {
  AllocationOptions options;
  int actuators = 0;
  std::vector<Pose> poses;
  std::vector<std::vector<int>> schemes;
  int rank_component = 3;  // index into kComponents
  int rank_direction = 0;  // index into options.directions
  std::string load_case;   // empty: none
};

// The analysis's spec at JSON pointer `pointer`, checked against the model (InputError naming the field).
Spec read_spec(const Model& model, const nlohmann::json& spec, const json_in::Pointer& pointer);

}  // namespace beamfea::allocation_spec
