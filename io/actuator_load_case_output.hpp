#pragma once
// results.json and CSV output of what a load case does to an actuation scheme (the
// `actuator_allocation` analysis with `load_case`; solvers/actuator_load_case.hpp).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "io/analysis.hpp"
#include "solvers/actuator_load_case.hpp"

namespace beamfea {

// The keys "actuator_efforts", "platform_displacement" and "loaded_stiffness" of one scheme at one pose.
void write_load_response(const Model& model, const AllocationOptions& options, const std::vector<int>& scheme,
                         const SchemeLoadResponse& r, ojson& pose_result);

// CSV rows "scheme,pose,joint,coordinate,effort" and
// "scheme,pose,direction,displacement_total,displacement_structural,displacement_actuated,
//  loaded_actuated,loaded_structural,loaded_total" (headers: the constants below).
inline constexpr const char* kEffortsCsvHeader = "scheme,pose,joint,coordinate,effort\n";
inline constexpr const char* kLoadCaseCsvHeader =
    "scheme,pose,direction,displacement_total,displacement_structural,displacement_actuated,loaded_actuated,"
    "loaded_structural,loaded_total\n";
std::string efforts_csv_rows(const Model& model, const AllocationOptions& options, const std::vector<int>& scheme,
                             const std::string& scheme_name, const std::string& pose, const SchemeLoadResponse& r);
std::string load_case_csv_rows(const AllocationOptions& options, const std::string& scheme_name, const std::string& pose,
                               const SchemeLoadResponse& r);

}  // namespace beamfea
