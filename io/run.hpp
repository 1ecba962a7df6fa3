#pragma once
// Running a model document: validate, run each analysis, write DIR/results.json and each
// analysis's own files. Outputs are staged inside DIR and moved into place when the run ends:
// bad input (InputError, exit 2) leaves DIR as it was; an analysis that fails (exit 1) still
// gives results.json and the files of the others.
#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/analysis.hpp"
#include "io/model_reader.hpp"
#include "core/parallel_tasks.hpp"

namespace beamfea {

struct RunOptions {
  std::filesystem::path out_dir;     // empty: no files at all
  bool write_vtk = true;
  std::vector<std::string> only;     // run only these analysis ids (empty: all); unknown: InputError
  MessageSink progress;              // progress lines (empty: silent)
  MessageSink warning;               // warnings (empty: dropped); each is also in RunReport::warnings
  // Whether the run looks for warnings at all (io/model_warnings.hpp, and the analyses': a path that
  // used up max_steps, an ill-conditioned stiffness, statically indeterminate constraint rows).
  // true: each goes to `warning` and into RunReport::warnings and results.json's "warnings" (an
  // array, empty when there are none). false (a sweep case: its base model's warnings are the
  // same every case): none is looked for and results.json has no "warnings".
  bool collect_warnings = true;
  // May be null. Set from another thread (a Python binding's, on Ctrl-C) to stop the run at its next
  // check: between analyses, at each step of a path, at each scheme of an actuator allocation.
  // run_document then throws RunCancelled and writes nothing (the staged files are removed).
  const std::atomic<bool>* cancel = nullptr;
  // May be null: incremented as each analysis ends (a progress display's count; read from any thread).
  std::atomic<std::size_t>* analyses_done = nullptr;
  ParallelTasks parallel;            // the program's threads (core/parallel_tasks.hpp; app/thread_tasks.hpp):
                                     // a linear analysis's element matrices beside its ordering, a large
                                     // results.json formatted in slices; empty: all on the calling thread
  // false: the caller reads results.json, not RunReport::results (the program). The analyses may
  // then make their largest objects (a linear analysis's nodes and members) only while results.json
  // is written, member by member, instead of holding them in the results tree
  // (io/deferred_results.hpp); RunReport::results lacks those objects. Without out_dir they are
  // never made (a process of a distributed run that runs the analyses and writes nothing).
  bool results_in_memory = true;
  // May be empty. Called once every output is staged (results.json included), just before they
  // are moved into place; an exception from it leaves DIR as it was. A program that runs one model
  // on several processes waits there until every process has finished its part.
  std::function<void()> before_commit;
  // May be empty. Called with what an analysis threw while running (after validation), before it
  // becomes that analysis's failure in results.json; it may throw instead, which ends the run
  // (nothing written). A program that runs one model on several processes ends them all there
  // for what may have struck one process alone: the others could be waiting for it.
  std::function<void(const std::string& analysis_id, const std::exception& error)> on_analysis_error;
};

// Thrown by run_document when RunOptions::cancel is set.
class RunCancelled : public std::runtime_error {
 public:
  RunCancelled() : std::runtime_error("the run was cancelled") {}
};

struct RunReport {
  ojson results;        // the whole results.json (less the deferred objects: RunOptions::results_in_memory)
  bool failed = false;  // some analysis failed (exit code 1)
  std::vector<std::pair<std::string, AnalysisOutcome>> outcomes;  // per analysis run, in order (result moved to `results`)
  std::vector<std::string> warnings;  // the run's warnings, in order (RunOptions::collect_warnings)
  // Kept from run to run by run_document's overload that writes over a report (null until then):
  // what the analyses reuse (io/analysis.hpp). Not part of the results.
  std::unique_ptr<RunWorkspace> workspace;
};

// Parses and validates a document into a model: the one validation that `check` and `run`
// share (the model, its contradictions, every analysis's needs). Throws InputError / ModelError.
Model load_and_check(const nlohmann::json& document);
// The same, read into `buffer` (reusing its storage, io/model_reader.hpp); the model is valid
// until the buffer's next read.
const Model& load_and_check(const nlohmann::json& document, ModelBuffer& buffer);

// Runs the analyses of an already-validated document.
RunReport run_document(const Model& model, const nlohmann::json& document, const RunOptions& options);
// The same, written over `report` (a caller running document after document, a sweep worker):
// its results object keeps its storage where the new results have the shape of the last ones
// (ObjectFiller), so that a small model's run allocates little or nothing for its results. The
// report afterwards is the one the other overload returns, value for value. The report also keeps
// what the analyses may reuse in the next run (RunReport::workspace: a small model's factorised
// linear system while only its loads change), results bit for bit those of a fresh run.
void run_document(const Model& model, const nlohmann::json& document, const RunOptions& options, RunReport& report);

}  // namespace beamfea
