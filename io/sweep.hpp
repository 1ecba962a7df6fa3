#pragma once
// Batch analyses: one base model, many cases, one results table (docs/sweep.md).
//
// A sweep file names a base model and the cases, either a grid (the Cartesian product of value
// lists, last axis fastest) or an explicit list. Each case changes a copy of the base document
// by JSON pointers set to values and/or by JSON Patch (RFC 6902), is validated by
// load_and_check and run by run_document, and contributes one row to DIR/cases.csv:
//
//   case, <parameters...>, <outputs, arrays flattened: name[i][j]...>, status, message, wall_time_s
//
// status is "ok", "analysis failed" or "bad input". Nothing here is analysis-specific: a case
// goes only through load_and_check and run_document.
//
// This library reads sweep files (io/sweep_reader.cpp), runs one case (run_sweep_case, below)
// and writes the table (io/sweep_table.hpp). The loop over the cases (threads, the MPI ranks'
// share, a stop flag and progress) is the program's: app/sweep_runner.hpp; signals, the
// launcher's environment, BLAS threads and the progress bar are cli/'s. A Python process that
// loads this library gets none of them.
//
// Glossary: *case index* is the position of a case in the sweep (grid order or list order);
// *case id* is its name in the table (the index for a grid, "id" or the index for a list).
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/analysis.hpp"
#include "io/editable_document.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"

namespace beamfea {

// One set of JSON pointers set to one value, or one JSON Patch; applied in order.
struct SweepChange {
  std::vector<nlohmann::json::json_pointer> pointers;  // set each to `value` (when patch is null)
  nlohmann::json value;
  nlohmann::json patch;  // an RFC 6902 operation array, or null
};

// One grid axis: "values" set at "pointer(s)", or one patch per value ("patches").
struct SweepAxis {
  std::string name;
  std::vector<nlohmann::json::json_pointer> pointers;
  std::vector<nlohmann::json> values;   // the column values (labels when patches are given)
  std::vector<nlohmann::json> patches;  // empty, or one patch per value
};

// One explicit case.
struct SweepListCase {
  std::string id;
  nlohmann::json parameters;  // object: column name -> value
  std::vector<SweepChange> changes;
};

// One collected output: a path into the case's results ("analyses.K.matrix",
// "analyses.lin.nodes.D.displacement[1]" or a JSON pointer "/analyses/K/matrix").
struct SweepOutput {
  // Array indices in output paths have at most this many digits (no array is that long; more would
  // overflow the conversion).
  static constexpr std::size_t kMaxIndexDigits = 9;
  std::string name;  // column name (prefix of the flattened columns)
  struct Token {
    std::string key;
    long index = -1;  // >= 0: an array index written [i]
  };
  std::vector<Token> path;
};

struct Sweep {
  std::filesystem::path base_path;   // as resolved (empty for an inline "model")
  nlohmann::json base;               // the base model document, parsed once
  std::vector<SweepAxis> grid;       // either a grid...
  std::vector<SweepListCase> list;   // ...or a list
  std::vector<std::string> parameter_names;
  std::vector<SweepOutput> outputs;
  std::vector<std::string> analyses;  // run only these analysis ids (empty: all)

  std::size_t size() const;
  std::string case_id(std::size_t index) const;
  // Parameter values of a case, one per parameter_names entry (null where a list case has none).
  std::vector<nlohmann::json> parameters(std::size_t index) const;
  // The value of parameter `k` (parameter_names[k]) in case `index`, in place (null where a list
  // case has none).
  const nlohmann::json& parameter(std::size_t index, std::size_t k) const;
  // The changes of a case, in the order they are applied.
  std::vector<SweepChange> changes(std::size_t index) const;
  // The case's document: the base with the case's changes applied (throws InputError).
  nlohmann::json document(std::size_t index) const;
  // Grid case `index`: the index of its value on `axis` (last axis fastest).
  std::size_t grid_value(std::size_t index, std::size_t axis) const;
};

// A worker's copy of the base document that each case changes in place and puts back afterwards
// (io/editable_document.hpp): a case copies only the values it changes, not the whole document (a
// small model's sweep spends as long copying the document as analysing it), and a warm case that
// sets values or replaces them by patches allocates nothing. A case whose changes do not apply in
// place gets a fresh copy (Sweep::document), which reports the error exactly as a fresh document does.
class SweepCaseDocument {
 public:
  explicit SweepCaseDocument(const Sweep& sweep) : sweep_(&sweep), doc_(sweep.base) {}
  // The case's document (throws InputError as Sweep::document); valid until the next call.
  const nlohmann::json& apply(std::size_t index);
  // Whether the last apply() changed the worker's copy in place (false: a fresh copy).
  bool in_place() const { return !fresh_; }

 private:
  const Sweep* sweep_;
  EditableDocument doc_;
  bool fresh_ = false;  // doc_ is a case's fresh copy: the base is copied back on the next call
};

// Reads a sweep document; relative "base" paths are resolved against `directory`.
// Every error is an InputError whose pointer names the entry of the sweep file at fault.
Sweep read_sweep(const nlohmann::json& doc, const std::filesystem::path& directory);
Sweep read_sweep_file(const std::string& path);

// The outcome of one case.
struct SweepCaseResult {
  enum class Status { Succeeded, AnalysisFailed, BadInput };
  Status status = Status::Succeeded;
  std::string message;
  double wall_time_s = 0.0;
  // Per output, its flattened (column name, cell text) pairs; empty where the path is absent.
  std::vector<std::vector<std::pair<std::string, std::string>>> outputs;
};
const char* to_string(SweepCaseResult::Status s);

// After a sweep that kept each case's files (DIR/cases/<id>/): for each stiffness analysis whose
// cases wrote a compliance ellipsoid, the series DIR/<analysis id>_ellipsoid.pvd of those files,
// time = case index, so that ParaView plays the ellipsoid across the cases (a workspace map).
void write_case_series(const Sweep& sweep, const std::filesystem::path& out_dir);

// Runs one case in process. keep_dir non-empty: results.json and VTK files written there.
// `documents` (may be null): the calling worker's SweepCaseDocument, reused from case to case.
SweepCaseResult run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir = {},
                               SweepCaseDocument* documents = nullptr);
// The same, written over `into` (the calling worker's, reused case after case: its output cells keep
// their strings' capacity). Every field of `into` is the case's own afterwards.
void run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
                    SweepCaseDocument* documents, SweepCaseResult& into);

// What a worker keeps from case to case: the case's document, the model read into a ModelBuffer
// and the results written over the last case's (run_document into a RunReport), so that a case
// of a small model allocates next to nothing (docs/performance.md).
struct SweepWorkspace {
  explicit SweepWorkspace(const Sweep& sweep) : document(sweep) {}
  SweepCaseDocument document;
  ModelBuffer model;
  RunReport report;
};
// The same, with the worker's workspace: the result is the other overloads', value for value.
void run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
                    SweepWorkspace& workspace, SweepCaseResult& into);

}  // namespace beamfea
