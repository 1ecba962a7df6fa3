#include "io/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "io/sweep_table.hpp"
#include "io/vtk_writer.hpp"

namespace beamfea {

using json = nlohmann::json;

namespace {

// An output value flattened into (column name, cell) pairs: name[i][j] for arrays, name.key for
// objects, written over out[n], out[n + 1], ... (their strings' capacity reused; `n` counts them).
// `name` is the caller's buffer (on its stack up to fmt's inline size): suffixes are appended and
// taken off again (no string per level).
void flatten(const ojson& v, fmt::memory_buffer& name, std::vector<std::pair<std::string, std::string>>& out,
             std::size_t& n) {
  const std::size_t length = name.size();
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      char index[24];
      index[0] = '[';
      char* end = std::to_chars(index + 1, index + sizeof index - 1, i).ptr;
      *end++ = ']';
      name.append(index, end);
      flatten(v[i], name, out, n);
      name.resize(length);
    }
  } else if (v.is_object()) {
    for (const auto& [k, x] : v.items()) {
      name.push_back('.');
      name.append(k.data(), k.data() + k.size());
      flatten(x, name, out, n);
      name.resize(length);
    }
  } else {
    if (n == out.size()) out.emplace_back();
    out[n].first.assign(name.data(), name.size());
    csv_cell_into(out[n].second, v);
    ++n;
  }
}

const ojson* find_path(const ojson& root, const SweepOutput& o) {
  const ojson* v = &root;
  for (const auto& t : o.path) {
    if (t.index >= 0 || (v->is_array() && !t.key.empty() &&
                         t.key.find_first_not_of("0123456789") == std::string::npos)) {
      if (t.index < 0 && t.key.size() > SweepOutput::kMaxIndexDigits) return nullptr;  // beyond any array
      const std::size_t i = t.index >= 0 ? static_cast<std::size_t>(t.index) : std::stoul(t.key);
      if (!v->is_array() || i >= v->size()) return nullptr;
      v = &(*v)[i];
    } else {
      if (!v->is_object()) return nullptr;
      auto it = v->find(t.key);
      if (it == v->end()) return nullptr;
      v = &*it;
    }
  }
  return v;
}

}  // namespace

const char* to_string(SweepCaseResult::Status s) {
  switch (s) {
    case SweepCaseResult::Status::Succeeded: return "ok";
    case SweepCaseResult::Status::AnalysisFailed: return "analysis failed";
    case SweepCaseResult::Status::BadInput: return "bad input";
  }
  return "?";
}

const json& SweepCaseDocument::apply(std::size_t index) {
  if (fresh_) {
    doc_.reset(sweep_->base);
    fresh_ = false;
  } else {
    doc_.restore();
  }
  bool in_place = true;
  auto set_all = [&](const std::vector<json::json_pointer>& pointers, const json& value) {
    for (const auto& p : pointers)
      if (in_place) in_place = doc_.set(p, value);
  };
  if (!sweep_->grid.empty()) {
    for (std::size_t a = 0; a < sweep_->grid.size() && in_place; ++a) {
      const auto& axis = sweep_->grid[a];
      const std::size_t v = sweep_->grid_value(index, a);
      if (!axis.patches.empty()) in_place = doc_.patch(axis.patches[v]);
      else set_all(axis.pointers, axis.values[v]);
    }
  } else {
    for (const auto& c : sweep_->list[index].changes) {
      if (!in_place) break;
      if (!c.patch.is_null()) in_place = doc_.patch(c.patch);
      else set_all(c.pointers, c.value);
    }
  }
  if (!in_place) {
    doc_.restore();
    doc_.reset(sweep_->document(index));  // throws the case's InputError
    fresh_ = true;
  }
  return doc_.doc();
}

namespace {

// A case; `documents`, `models` and `reports` (each may be null: fresh ones) are the calling
// worker's, reused case after case.
void run_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
              SweepCaseDocument* documents, ModelBuffer* models, RunReport* reports, SweepCaseResult& r) {
  const auto t0 = std::chrono::steady_clock::now();
  r.status = SweepCaseResult::Status::Succeeded;
  r.message.clear();
  r.outputs.resize(sweep.outputs.size());
  std::size_t done = 0;  // outputs written for this case; those after it still hold the last case's
  auto fail = [&](SweepCaseResult::Status status, const char* what) {
    r.status = status;
    r.message = what;
    for (std::size_t o = done; o < r.outputs.size(); ++o) r.outputs[o].clear();
  };
  try {
    json copy;
    const json& doc = documents ? documents->apply(index) : (copy = sweep.document(index));
    std::optional<Model> fresh_model;
    const Model& model = models ? load_and_check(doc, *models) : fresh_model.emplace(load_and_check(doc));
    RunOptions opt;
    opt.out_dir = keep_dir;
    opt.write_vtk = !keep_dir.empty();
    opt.only = sweep.analyses;
    // A case's row has no place for warnings; the results.json of a kept case lists them.
    opt.collect_warnings = !keep_dir.empty();
    RunReport fresh_report;
    RunReport& report = reports ? *reports : fresh_report;
    run_document(model, doc, opt, report);
    std::string missing;
    for (; done < sweep.outputs.size(); ++done) {
      auto& out = r.outputs[done];
      if (const ojson* v = find_path(report.results, sweep.outputs[done])) {
        const std::string& prefix = sweep.outputs[done].name;
        fmt::memory_buffer name;
        name.append(prefix.data(), prefix.data() + prefix.size());
        std::size_t n = 0;
        flatten(*v, name, out, n);
        out.resize(n);
      } else {
        out.clear();
        missing += (missing.empty() ? "" : ", ") + sweep.outputs[done].name;
      }
    }
    if (report.failed) {
      r.status = SweepCaseResult::Status::AnalysisFailed;
      for (const auto& [id, a] : report.results["analyses"].items()) {
        if (!a.is_object() || !a.contains("status") || a["status"] == "ok") continue;
        const std::string m = a.contains("message") && a["message"].is_string() ? a["message"].get<std::string>()
                                                                                : a["status"].dump();
        r.message += (r.message.empty() ? "" : "; ") + id + ": " + m;
      }
      if (r.message.empty()) r.message = "an analysis failed";
    } else if (!missing.empty()) {
      r.message = "not in the results: " + missing;
    }
  } catch (const InputError& e) {
    fail(SweepCaseResult::Status::BadInput, e.what());
  } catch (const ModelError& e) {
    fail(SweepCaseResult::Status::BadInput, e.what());
  } catch (const std::exception& e) {
    fail(SweepCaseResult::Status::AnalysisFailed, e.what());
  }
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SweepCaseResult run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
                               SweepCaseDocument* documents) {
  SweepCaseResult r;
  run_sweep_case(sweep, index, keep_dir, documents, r);
  return r;
}

void run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
                    SweepCaseDocument* documents, SweepCaseResult& into) {
  run_case(sweep, index, keep_dir, documents, nullptr, nullptr, into);
}

void run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
                    SweepWorkspace& workspace, SweepCaseResult& into) {
  run_case(sweep, index, keep_dir, &workspace.document, &workspace.model, &workspace.report, into);
}

void write_case_series(const Sweep& sweep, const std::filesystem::path& out_dir) {
  const nlohmann::json* analyses = json_in::field(sweep.base, "analyses");
  if (!analyses || !analyses->is_array()) return;
  for (const auto& a : *analyses) {
    const nlohmann::json* type = json_in::field(a, "type");
    const nlohmann::json* id = json_in::field(a, "id");
    if (!type || *type != "stiffness" || !id || !id->is_string()) continue;
    const std::string name = id->get<std::string>();
    if (!sweep.analyses.empty() && std::find(sweep.analyses.begin(), sweep.analyses.end(), name) == sweep.analyses.end())
      continue;
    const std::string file = name + "_ellipsoid.vtp";
    std::vector<std::pair<double, std::string>> entries;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      const std::filesystem::path relative = std::filesystem::path("cases") / sweep.case_id(i) / file;
      if (std::filesystem::exists(out_dir / relative)) entries.emplace_back(static_cast<double>(i), relative.generic_string());
    }
    if (!entries.empty()) write_pvd((out_dir / (name + "_ellipsoid.pvd")).string(), entries);
  }
}

}  // namespace beamfea
