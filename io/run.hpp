#pragma once
// Running a model document: validate, run each analysis, write DIR/results.json and each
// analysis's own files. Outputs are staged inside DIR and moved into place when the run ends:
// bad input (InputError, exit 2) leaves DIR as it was; an analysis that fails (exit 1) still
// gives results.json and the files of the others.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/analysis.hpp"

namespace beamfea {

struct RunOptions {
  std::filesystem::path out_dir;     // empty: no files at all
  bool write_vtk = true;
  std::vector<std::string> only;     // run only these analysis ids (empty: all); unknown: InputError
  MessageSink progress;              // progress lines (empty: silent)
  MessageSink warning;               // warnings (empty: dropped)
};

struct RunReport {
  ojson results;        // the whole results.json
  bool failed = false;  // some analysis failed (exit code 1)
  std::vector<std::pair<std::string, AnalysisOutcome>> outcomes;  // per analysis run, in order (result moved to `results`)
};

// Parses and validates a document into a model: the one validation that `check` and `run`
// share (the model, its contradictions, every analysis's needs). Throws InputError / ModelError.
Model load_and_check(const nlohmann::json& document);

// Runs the analyses of an already-validated document.
RunReport run_document(const Model& model, const nlohmann::json& document, const RunOptions& options);

}  // namespace beamfea
