#pragma once
// The result writers that linear_static and second_order share (io/analysis_linear.cpp,
// io/analysis_second_order.cpp): a static solution's nodes, members (end forces, stations,
// segments), joints, mechanism modes and .vtu.
#include <memory>
#include <string>
#include <vector>

#include "io/analysis.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/mechanism.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/second_order.hpp"

namespace beamfea {

// The zero-energy modes as [{description, nodes, elements, joints, dofs}] (ids).
ojson mechanism_json(const Model& model, const std::vector<ZeroEnergyMode>& modes);

// Which solver ran, written over `v`: {"type": "direct" | "iterative", "iterations", "residual"}
// (analyses.<id>.solver; docs/analyses/solver.md).
void set_solver_report(ojson& v, const SolverReport& report);

// An analysis spec's "stations" (interior stations per member, default 10, at most 10000),
// InputError at <p>/stations naming `type`.
int read_stations(const nlohmann::json& spec, const json_in::Pointer& p, const std::string& type);

// Writes `held`'s nodes, elements, joints, statically_indeterminate and (with an output folder)
// vtk into `res`. The deferred parts (ctx.deferred) share `held`; the station storage is the
// caller's.
void set_static_solution(ObjectFiller& res, const AnalysisContext& ctx, std::shared_ptr<const LinearStaticResult> held,
                         int stations, std::vector<Station>& station_storage, std::vector<double>& position_storage);

// The spec's "about" ("linear_static", the default, or "second_order") and "geometric_stiffness"
// ("full", the default, or "axial") of an analysis about a load case (modal, stiffness): InputError
// at the field when the spec names no load case (`loaded` false) or an unknown value.
PreloadOptions read_preload(const nlohmann::json& spec, const json_in::Pointer& p, const std::string& type, bool loaded);

// A static analysis iterated by solvers/second_order.hpp (second_order, or linear_static of a model
// with tension-only or compression-only members), its result analyses.<id> of type `type`.
AnalysisOutcome run_iterated_static(const AnalysisContext& ctx, const std::string& type, const std::string& load_case,
                                    int stations, const SecondOrderOptions& options);

}  // namespace beamfea
