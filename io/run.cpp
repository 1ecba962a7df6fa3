#include "io/run.hpp"

#include <algorithm>
#include <chrono>
#include <optional>

#include "core/errors.hpp"
#include "core/version.hpp"
#include "io/atomic_file.hpp"
#include "io/json_util.hpp"
#include "io/json_writer.hpp"
#include "io/model_check.hpp"
#include "io/model_reader.hpp"
#include "io/model_warnings.hpp"
#include "io/result_status.hpp"
#include "solvers/linear_static.hpp"

namespace beamfea {

namespace {
// What `check` and `run` validate after reading: the model's contradictions, every analysis's needs.
void check_document(const Model& m, const nlohmann::json& document) {
  check_model(m, document);
  check_analyses(m, document);
}
}  // namespace

Model load_and_check(const nlohmann::json& document) {
  Model m = read_model(document);
  check_document(m, document);
  return m;
}

const Model& load_and_check(const nlohmann::json& document, ModelBuffer& buffer) {
  const Model& m = buffer.read(document);
  check_document(m, document);
  return m;
}

namespace {

// Runs one analysis; a ModelError or solver error raised while running (after validation) is
// that analysis's failure, reported in results.json, not a crash of the run.
AnalysisOutcome run_one(const AnalysisType& type, const AnalysisContext& ctx, const nlohmann::json& spec,
                        const RunOptions& options) {
  AnalysisOutcome o;
  try {
    o = type.run(ctx, spec);
  } catch (const InputError&) {
    throw;  // bad input found late is still bad input
  } catch (const RunCancelled&) {
    throw;  // the caller stopped the run: no result at all
  } catch (const std::exception& e) {
    if (options.on_analysis_error) options.on_analysis_error(ctx.id, e);
    o = AnalysisOutcome{};
    o.result["type"] = type.name;
    o.result["status"] = kFailedStatus;
    o.result["message"] = e.what();
    o.termination = AnalysisTermination::Failed;
    o.message = e.what();
    return o;
  }
  if (const std::string where = first_non_finite(o.result, "", ctx.deferred); !where.empty()) {
    o.termination = AnalysisTermination::NonFiniteResult;
    o.message = "the result is not finite at '" + where +
                "' (an overflow: values or stiffnesses too far apart for double precision)";
    o.result["status"] = kFailedStatus;
    o.result["message"] = o.message;
  }
  return o;
}

// "pose": every joint's coordinates (a number for a one-coordinate joint) and every node's posed
// position (docs/poses.md).
void write_pose(ojson& out, const Model& model) {
  ObjectFiller pose(out, 2);
  ObjectFiller joints(pose.slot("joints"), model.joints.size());
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const Eigen::VectorXd& q = model.pose.solved[j];
    ojson& v = joints.slot(model.joints[j].id);
    if (q.size() == 1) v = q[0];
    else set_numbers(v, q.data(), static_cast<std::size_t>(q.size()));
  }
  joints.finish();
  ObjectFiller nodes(pose.slot("nodes"), model.nodes.size());
  for (const auto& n : model.nodes) set_numbers(nodes.slot(n.id), n.x.data(), 3);
  nodes.finish();
  pose.finish();
}

// An analysis's statically indeterminate constraint rows (its result's "statically_indeterminate",
// the DOF map's redundant closure rows) as a warning, or "" when it has none.
std::string indeterminate_warning(const std::string& id, const ojson& result) {
  const auto it = result.find("statically_indeterminate");
  if (it == result.end() || !it->is_array() || it->empty()) return {};
  std::string names;
  std::size_t k = 0;
  for (const auto& row : *it) {
    if (k == kMaxIdsPerWarning) {
      names += " and " + std::to_string(it->size() - k) + " more";
      break;
    }
    names += (k++ ? ", " : "") + (row.is_string() ? row.get<std::string>() : row.dump());
  }
  return "analysis '" + id + "': " + std::to_string(it->size()) + " constraint row" + (it->size() == 1 ? " is" : "s are") +
         " redundant (" + names + "): their reactions are statically indeterminate, and the ones reported are the "
         "minimum-norm split";
}

// Both overloads: `workspace` null for a fresh run (nothing kept afterwards).
void run_into(const Model& model, const nlohmann::json& document, const RunOptions& options, RunReport& report,
              RunWorkspace* workspace);

}  // namespace

RunReport run_document(const Model& model, const nlohmann::json& document, const RunOptions& options) {
  RunReport report;
  run_into(model, document, options, report, nullptr);
  return report;
}

void run_document(const Model& model, const nlohmann::json& document, const RunOptions& options, RunReport& report) {
  if (!report.workspace) report.workspace = std::make_unique<RunWorkspace>();
  run_into(model, document, options, report, report.workspace.get());
}

namespace {

void run_into(const Model& model, const nlohmann::json& document, const RunOptions& options, RunReport& report,
              RunWorkspace* workspace) {
  report.failed = false;
  report.warnings.clear();
  const auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
  MessageSink warn;
  if (options.collect_warnings)
    warn = [&](const std::string& s) {
      report.warnings.push_back(s);
      if (options.warning) options.warning(s);
    };
  if (options.collect_warnings)
    for (const std::string& w : model_warnings(model)) warn(w);
  // The outcomes are written over the last run's, in order (their strings keep their storage);
  // those beyond this run's count are dropped at the end.
  std::size_t outcomes = 0;
  struct DropStale {  // also when bad input found late ends the run: only this run's outcomes stay
    RunReport& report;
    const std::size_t& count;
    ~DropStale() { report.outcomes.resize(count); }
  } drop_stale{report, outcomes};
  // Written over the report's last results (ObjectFiller: a reused report's storage is reused),
  // objects with room for their keys: an ordered_json object that grows deep copies what it holds
  // (for a small model building the results costs as much as the analysis).
  ObjectFiller results(report.results, 4);
  set_string(results.slot("beamfea"), kVersion);
  ObjectFiller counts(results.slot("model"), 4);
  counts.slot("nodes") = model.nodes.size();
  counts.slot("elements") = model.elements.size();
  counts.slot("members") = model.members.size();
  counts.slot("joints") = model.joints.size();
  counts.finish();
  if (model.pose.given) write_pose(results.slot("pose"), model);
  const auto& specs = document.at("analyses");
  report.outcomes.reserve(specs.size());
  for (std::size_t k = 0; k < options.only.size(); ++k) {
    const bool known = std::any_of(specs.begin(), specs.end(), [&](const auto& s) {
      return json_in::id(s.at("id"), "", "analysis") == options.only[k];
    });
    if (!known) throw InputError("", "--analysis '" + options.only[k] + "': no analysis of that id in the model");
  }
  std::optional<StagingDir> staging;
  if (!options.out_dir.empty()) staging.emplace(options.out_dir);
  ObjectFiller analyses(results.slot("analyses"), specs.size());
  // The objects the analyses defer when nobody reads the results tree: made while results.json is
  // written (io/deferred_results.hpp), or never when nothing is written (a process of a
  // distributed run other than rank 0, whose tree would otherwise hold every node's and member's
  // numbers: 0.64 GB at 403,440 DOFs).
  DeferredParts deferred;
  DeferredParts* defer = !options.results_in_memory ? &deferred : nullptr;
  RunCache cache;
  cache.workspace = workspace;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto& spec = specs[i];
    const std::string id = json_in::id(spec.at("id"), "", "analysis");
    if (!options.only.empty() && std::find(options.only.begin(), options.only.end(), id) == options.only.end())
      continue;
    if (cancelled()) throw RunCancelled();
    const AnalysisType* type = find_analysis_type(spec.at("type").get_ref<const std::string&>());
    ojson& result = analyses.slot(id);  // the last run's result of this id, or null
    std::string* previous_message = outcomes < report.outcomes.size() ? &report.outcomes[outcomes].second.message : nullptr;
    AnalysisContext ctx{model, json_in::child("/analyses", i), id, staging ? staging->path() : std::filesystem::path(),
                        options.write_vtk, {}, warn, &cache, &result, previous_message, defer, options.parallel};
    // The analyses' progress points are where a cancelled run stops.
    if (options.progress || options.cancel)
      ctx.progress = [&](const std::string& s) {
        if (cancelled()) throw RunCancelled();
        if (options.progress) options.progress("[" + id + "] " + s);
      };
    const auto t0 = std::chrono::steady_clock::now();
    AnalysisOutcome o = run_one(*type, ctx, spec, options);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    o.result["wall_time_s"] = dt;
    if (options.progress) options.progress("[" + id + "] " + o.brief_report() + " (" + std::to_string(dt) + " s)");
    report.failed = report.failed || o.failed();
    if (warn)
      if (std::string w = indeterminate_warning(id, o.result); !w.empty()) warn(w);
    result = std::move(o.result);
    o.result = ojson();
    if (outcomes < report.outcomes.size()) {
      report.outcomes[outcomes].first.assign(id);
      report.outcomes[outcomes].second = std::move(o);
    } else {
      report.outcomes.emplace_back(id, std::move(o));
    }
    ++outcomes;
    if (options.analyses_done) options.analyses_done->fetch_add(1);
  }
  analyses.finish();
  if (cancelled()) throw RunCancelled();
  if (cache.linear) results.slot("factorizations") = cache.linear->factorizations();
  if (options.collect_warnings) set_strings(results.slot("warnings"), report.warnings);
  results.finish();
  if (staging) {
    write_results_json_file(report.results, staging->path() / "results.json", options.parallel, defer);
    if (options.before_commit) options.before_commit();
    staging->commit("results.json");
  }
  deferred.erase_placeholders(report.results);
}

}  // namespace

}  // namespace beamfea
