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
// status is "ok", "analysis failed" or "bad input". Rows are appended (one write per batch of
// whole rows) as cases finish, so the table is valid CSV at every moment; at the end it is
// sorted by case order and rewritten atomically. Nothing here is analysis-specific: the sweep
// goes only through load_and_check and run_document.
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
  // The changes of a case, in the order they are applied.
  std::vector<SweepChange> changes(std::size_t index) const;
  // The case's document: the base with the case's changes applied (throws InputError).
  nlohmann::json document(std::size_t index) const;
};

// Reads a sweep document; relative "base" paths are resolved against `directory`.
// Every error is an InputError whose pointer names the entry of the sweep file at fault.
Sweep read_sweep(const nlohmann::json& doc, const std::filesystem::path& directory);
Sweep read_sweep_file(const std::string& path);

// The outcome of one case.
struct SweepCaseResult {
  enum class Status { Ok, AnalysisFailed, BadInput };
  Status status = Status::Ok;
  std::string message;
  double wall_time_s = 0.0;
  // Per output, its flattened (column name, cell text) pairs; empty where the path is absent.
  std::vector<std::vector<std::pair<std::string, std::string>>> outputs;
};
const char* to_string(SweepCaseResult::Status s);

// Runs one case in process. keep_dir non-empty: results.json and VTK files written there.
SweepCaseResult run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir = {});

// Transport between the processes of a multi-process sweep (MPI lives in the program, so that
// this library does not depend on it). Rank 0 writes the table; the others send it rows.
class SweepComm {
 public:
  virtual ~SweepComm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Rank 0's text to every rank.
  virtual void broadcast(std::string& text) = 0;
  // Not rank 0: sends a batch of rows to rank 0; `last` marks this rank's final batch.
  virtual void send(const std::string& batch, bool last) = 0;
  // Rank 0: receives one pending batch if there is one (does not block).
  virtual bool receive(std::string& batch, bool& last) = 0;
};

enum class SweepProgress { Auto, Bar, Lines, None };

struct SweepOptions {
  std::filesystem::path out_dir = "out";
  int jobs = 0;             // worker threads (0: all cores, divided among the ranks on one host)
  bool keep = false;        // per-case results.json and VTK in DIR/cases/<id>/
  bool resume = false;      // skip the cases already in DIR/cases.csv
  SweepProgress progress = SweepProgress::Auto;  // Auto: a bar on a terminal, lines otherwise
  double line_interval_s = 5.0;                  // period of the plain progress lines
  void validate() const;
};

struct SweepSummary {
  std::size_t cases = 0;     // in the sweep
  std::size_t skipped = 0;   // already in the table (--resume)
  std::size_t ran = 0;       // run now (all ranks)
  std::size_t ok = 0, analysis_failed = 0, bad_input = 0;  // over the whole table
  int processes = 1;         // MPI ranks
  bool interrupted = false;  // SIGINT/SIGTERM: the table holds the finished cases
  double wall_time_s = 0.0;
  std::filesystem::path table;
  std::string report() const;  // one line
  // 0 every case ok; 1 some case failed (see the table); 130 interrupted.
  int exit_code() const;
};

// Runs the sweep (all ranks of `comm` call it; null: one process). Throws InputError for a
// bad sweep or a table that --resume cannot continue.
SweepSummary run_sweep(const Sweep& sweep, const SweepOptions& options, SweepComm* comm = nullptr);

// RFC 4180 field quoting, and splitting one line of such a table.
std::string csv_field(const std::string& s);
std::vector<std::string> csv_split(const std::string& line);

}  // namespace beamfea
