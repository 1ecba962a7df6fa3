#pragma once
// Analyses read from "analyses": [{"id": ..., "type": ...}, ...].
//
// Each type registers one reader of its spec into its own Spec struct (options, load case,
// outputs; validated against the model: InputError with the JSON pointer) and a run function that
// receives that Spec, never the raw JSON (it returns the JSON object stored at analyses.<id> in
// results.json and writes its own files into the output folder, each atomically). The registry is
// in io/analysis_registry.cpp: one line per analysis type, made by register_analysis<Spec>.
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "io/deferred_results.hpp"
#include "io/json_pointer.hpp"
#include "core/parallel_tasks.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/structure_cache.hpp"

namespace beamfea {

using ojson = nlohmann::ordered_json;

// The documented bound of "modes" of the buckling and modal analyses (docs/analyses/).
inline constexpr int kMaxModes = 1000;

// Where messages go: progress lines and warnings reach the caller through sinks it chooses (the
// program prints them on stderr; a library caller may collect or drop them). Empty: dropped.
using MessageSink = std::function<void(const std::string&)>;

// What a RunReport reused run after run (a sweep worker's, io/run.hpp) keeps for its analyses: a
// small model's linear system while its structure stays the same (a load sweep factorises once:
// solvers/structure_cache.hpp), and the storage of the last linear solution and of its stations,
// and of the last node stiffness (its directions and names).
struct RunWorkspace {
  LinearSystemCache systems;
  LinearStaticResult linear;
  LinearSolveScratch linear_scratch;
  std::vector<Station> stations;
  std::vector<double> station_positions;
  CondensedStiffness stiffness;
};

// Shared by the analyses of one run: the model's linear system, factorised once for all the load
// cases of its linear analyses (made by the first analysis that needs it).
struct RunCache {
  std::shared_ptr<const LinearSystem> linear;
  RunWorkspace* workspace = nullptr;  // may be null: nothing kept from the last run
};

struct AnalysisContext {
  const Model& model;
  std::string pointer;              // "/analyses/<i>"
  std::string id;                   // a safe file-name stem (check_analyses: analysis_id)
  std::filesystem::path out_dir;    // empty: write no files (sweeps, tests); a staging folder
                                    // under a run (run_document moves the files into place)
  bool write_vtk = true;
  MessageSink progress;             // may be empty
  MessageSink warning;              // may be empty
  RunCache* cache = nullptr;       // may be null: nothing shared
  // May be null: this analysis's result in the previous run of a reused RunReport (run_document's
  // overload that writes into one), whose storage the analysis may take for its result (moved
  // out, written over with ObjectFiller) or leave.
  ojson* previous_result = nullptr;
  // May be null: the message of the outcome at this position in that previous run, whose storage
  // the analysis may take for its own message (swapped out) or leave.
  std::string* previous_message = nullptr;
  // May be null (results read from the tree): where the analysis may defer a large object of its
  // result, to be made only while results.json is written (io/deferred_results.hpp). What a
  // deferred object's members are made from must outlive the run (the model does; the analysis's
  // own arrays are held by the part).
  DeferredParts* deferred = nullptr;
  // The program's threads (RunOptions::parallel: the linear analysis computes its element matrices
  // beside the ordering of the stiffness's pattern); empty: all on the calling thread.
  ParallelTasks parallel;
};

// How an analysis ended. results.json keeps its own "status" strings (a contract); this is the
// program's vocabulary for the exit code and the one-line reports.
enum class AnalysisTermination {
  Succeeded,        // an answer (including "no buckling", "no free DOF")
  Mechanism,        // the structure (or the condensation) is a mechanism: modes listed
  NotConverged,     // an iterative solution or a path stopped short
  NonFiniteResult,  // a result overflowed (inf/NaN): reported as a failure, never as null
  Failed,           // any other failure; the message says why
};
const char* to_string(AnalysisTermination t);

struct AnalysisOutcome {
  ojson result;          // analyses.<id>
  AnalysisTermination termination = AnalysisTermination::Succeeded;
  std::string message;
  bool failed() const { return termination != AnalysisTermination::Succeeded; }
  // One line: "succeeded: <message>" or "<termination>: <message>".
  std::string brief_report() const;
};

// The files an analysis may write into the output folder, named from its id: whole names
// ("<id>.vtu", "<id>.pvd") and numbered families "<stem><k>.vtu" (k = 0, 1, 2 ... written
// without leading zeros; the stem ends in a letter, "<id>_mode"). check_analyses rejects two
// analyses whose files could have one name ("a" buckling writes a_mode1.vtu, and so
// would an analysis "a_mode1").
struct AnalysisFiles {
  std::vector<std::string> names;
  std::vector<std::string> numbered_vtu_stems;
};

struct AnalysisType {
  std::string name;
  // Validates the spec against the model, covering everything the run needs that input can decide
  // without solving (InputError with the JSON pointer): the type's reader, its Spec discarded.
  std::function<void(const Model&, const nlohmann::json& spec, const json_in::Pointer& pointer)> check;
  // Reads the spec of a checked document with the same reader, on the stack (a sweep case allocates
  // nothing for it), and runs the analysis of that Spec.
  std::function<AnalysisOutcome(const AnalysisContext&, const nlohmann::json& spec)> run;
  // Every file `run` may write for an analysis of this id (empty: it writes none).
  std::function<AnalysisFiles(const std::string& id)> files;
};

// An analysis type of one reader, `read` (the raw JSON into a Spec, validated), and one run
// function, `run`, that takes the Spec.
template <class Spec>
AnalysisType register_analysis(std::string name, Spec (*read)(const Model&, const nlohmann::json&, const json_in::Pointer&),
                               AnalysisOutcome (*run)(const AnalysisContext&, const Spec&),
                               std::function<AnalysisFiles(const std::string& id)> files) {
  return {std::move(name), [read](const Model& m, const nlohmann::json& spec, const json_in::Pointer& p) { read(m, spec, p); },
          [read, run](const AnalysisContext& ctx, const nlohmann::json& spec) {
            return run(ctx, read(ctx.model, spec, ctx.pointer));
          },
          std::move(files)};
}

const std::vector<AnalysisType>& analysis_types();
const AnalysisType* find_analysis_type(const std::string& name);

// Validates every analysis spec (at least one; ids unique and safe as file names, types known,
// each type's check).
void check_analyses(const Model& model, const nlohmann::json& document);

// Throws InputError at the later analysis's id when two analyses (id, pointer "/analyses/<i>",
// type) could write files of one name, naming both pointers and the file.
struct AnalysisFileOwner {
  std::string id;
  std::string pointer;
  const AnalysisType* type = nullptr;
};
void check_file_clashes(const std::vector<AnalysisFileOwner>& analyses);

// Analysis ids become file names (DIR/<id>.vtu, DIR/<id>_mode1.vtu ...): letters, digits and
// _ - . + = only, not "." or "..", at most kMaxAnalysisIdLength characters. Returns the id of
// `v` or throws InputError at `pointer`.
inline constexpr std::size_t kMaxAnalysisIdLength = 64;
std::string analysis_id(const nlohmann::json& v, const json_in::Pointer& pointer);

// The model restrictions of the nonlinear analyses (buckling, path), as the nonlinear structure
// states them, as an InputError at the analysis's pointer `p`.
void check_nonlinear_model(const Model& model, const json_in::Pointer& p);

// The first non-finite number in a result ("" when all are finite), as a path "a.b[2]"; the
// members of deferred objects included (their placeholders in `v` are looked up in `deferred`).
std::string first_non_finite(const ojson& v, const std::string& path = "", const DeferredParts* deferred = nullptr);

// Helpers shared by the analyses' JSON output.
ojson to_json(const Vec3& v);
ojson to_json(const Vec6& v);
ojson to_json(const Eigen::VectorXd& v);
ojson to_json(const Mat6& m);
// Any dense matrix as an array of rows (a named function: Eigen expressions would make a to_json
// overload ambiguous).
ojson matrix_to_json(const Eigen::MatrixXd& m);
// Appends key: value to a JSON object without searching its keys (ordered_json's operator[] and
// emplace search linearly, so an object of n ids built by them costs O(n^2): 12.5 s at 2e5 DOFs).
// The caller guarantees the key is new (ids are unique within a collection of the model).
void append_new_key(ojson& object, const std::string& key, ojson value);
// An empty object with room for n keys: appending then never reallocates, which matters because
// ordered_json's (const key, value) pairs are copied, not moved, when its vector grows (a deep
// copy of every subtree already in the object).
ojson object_with_capacity(std::size_t n);

// Writes a JSON object key by key over what it held before (a results object reused run after
// run, RunReport): where the object held the key being written at that position, the value there
// is handed back to be overwritten (with the set_* helpers below, strings and arrays keep their
// storage); otherwise the keys from that position on are dropped and the key is appended.
// finish() drops the keys not written. The values written are those of a fresh object, in the
// same order: only where storage comes from differs.
class ObjectFiller {
 public:
  // `object` becomes an object (with room for `keys` keys) if it is not one.
  ObjectFiller(ojson& object, std::size_t keys);
  // The value at `key`: the old one (to overwrite), or a new null one. Valid until the next slot().
  ojson& slot(std::string_view key);
  void finish();

 private:
  ojson::object_t::Container& items_;
  std::size_t next_ = 0;  // keys written so far
};
// Values written over `v` (its storage reused when it already holds that shape), the same as
// assigning the fresh value: a string; numbers (an array); a 6x6 matrix (an array of 6 rows);
// vectors (an array of arrays); strings (an array); an array of n values to fill.
void set_string(ojson& v, std::string_view s);
void set_numbers(ojson& v, const double* p, std::size_t n);
void set_matrix(ojson& v, const Mat6& m);
void set_vectors(ojson& v, const std::vector<Vec6>& vectors);
void set_strings(ojson& v, const std::vector<std::string>& strings);
// `v` as an array of n values (those it held kept, to be written over), returned.
ojson::array_t& set_array(ojson& v, std::size_t n);

// Registered analyses (io/analysis_*.cpp).
AnalysisType linear_static_analysis();
AnalysisType stiffness_analysis();
AnalysisType actuator_allocation_analysis();
AnalysisType buckling_analysis();
AnalysisType path_analysis();
AnalysisType modal_analysis();
AnalysisType second_order_analysis();
AnalysisType superelement_analysis();
AnalysisType frf_analysis();
AnalysisType transient_analysis();

}  // namespace beamfea
