#pragma once
// Analyses read from "analyses": [{"id": ..., "type": ...}, ...].
//
// Each type registers a `check` (validates its spec against the model: InputError with the
// JSON pointer) and a `run` (returns the JSON object stored at analyses.<id> in results.json and
// writes its own files into the output folder, each atomically). The registry is in
// io/analysis_registry.cpp: one line per analysis type.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model.hpp"

namespace beamfea {

using ojson = nlohmann::ordered_json;

struct AnalysisContext {
  const Model& model;
  const nlohmann::json& document;   // the whole input document
  const nlohmann::json& spec;       // this analysis's object
  std::string pointer;              // "/analyses/<i>"
  std::string id;
  std::filesystem::path out_dir;    // empty: write no files (sweeps, tests)
  bool write_vtk = true;
  std::function<void(const std::string&)> progress;  // may be empty
};

struct AnalysisOutcome {
  ojson result;          // analyses.<id>
  bool failed = false;   // the analysis ran but did not succeed (mechanism, no convergence)
  std::string message;
};

struct AnalysisType {
  std::string name;
  std::function<void(const Model&, const nlohmann::json& spec, const std::string& pointer)> check;
  std::function<AnalysisOutcome(const AnalysisContext&)> run;
};

const std::vector<AnalysisType>& analysis_types();
const AnalysisType* find_analysis_type(const std::string& name);

// Validates every analysis spec (ids unique, types known, fields valid).
void check_analyses(const Model& model, const nlohmann::json& document);

// Helpers shared by the analyses' JSON output.
ojson to_json(const Vec3& v);
ojson to_json(const Vec6& v);
ojson to_json(const Eigen::VectorXd& v);
ojson to_json(const Mat6& m);

// Registered analyses (io/analysis_*.cpp).
AnalysisType linear_static_analysis();
AnalysisType stiffness_analysis();
AnalysisType actuator_allocation_analysis();
AnalysisType buckling_analysis();
AnalysisType path_analysis();

}  // namespace beamfea
