#pragma once
// Running a model document: validate, run each analysis, write DIR/results.json (atomically,
// after all analyses) and each analysis's own files.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/analysis.hpp"

namespace beamfea {

struct RunOptions {
  std::filesystem::path out_dir;     // empty: no files at all
  bool write_vtk = true;
  bool verbose = false;              // progress lines on stderr
  std::vector<std::string> only;     // run only these analysis ids (empty: all)
};

struct RunReport {
  ojson results;        // the whole results.json
  bool failed = false;  // some analysis failed (exit code 1)
};

// Parses and validates a document into a model (throws InputError / ModelError).
Model load_and_check(const nlohmann::json& document);

// Runs the analyses of an already-validated document.
RunReport run_document(const Model& model, const nlohmann::json& document, const RunOptions& options);

}  // namespace beamfea
