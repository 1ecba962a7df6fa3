#include "io/sweep.hpp"

#include <fmt/format.h>

#include <charconv>
#include <chrono>
#include <optional>
#include <string>

#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "io/sweep_table.hpp"

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
    case SweepCaseResult::Status::Ok: return "ok";
    case SweepCaseResult::Status::AnalysisFailed: return "analysis failed";
    case SweepCaseResult::Status::BadInput: return "bad input";
  }
  return "?";
}

namespace {

// Whether a value is held in the json object itself (nothing on the heap).
bool inline_value(const json& v) { return v.is_null() || v.is_boolean() || v.is_number(); }

// to = from, written into `to`'s storage where the shapes agree: inline values, strings (the
// string's capacity), arrays of the same length (element by element). Elsewhere (objects, a change
// of kind or length) a plain assignment, which allocates. `to` equals `from` afterwards either way.
void assign_in_place(json& to, const json& from) {
  if (inline_value(to) && inline_value(from)) {
    to = from;  // copies the type and the number as they are (integer, unsigned, float)
  } else if (to.is_string() && from.is_string()) {
    to.get_ref<std::string&>() = from.get_ref<const std::string&>();
  } else if (to.is_array() && from.is_array() && to.size() == from.size()) {
    for (std::size_t i = 0; i < from.size(); ++i) assign_in_place(to[i], from[i]);
  } else {
    to = from;
  }
}

}  // namespace

bool SweepCaseDocument::set(const json::json_pointer& p, const json& value) {
  // One traversal: `at` throws (out_of_range, or parse_error for an index that is not one) exactly
  // where `contains` says false, and a sweep sets its pointers for every case.
  json* slot = nullptr;
  try {
    slot = &doc_.at(p);
  } catch (const json::exception&) {
    return false;  // Sweep::document names the error
  }
  if (n_saved_ == saved_.size()) saved_.emplace_back();
  auto& [pointer, old] = saved_[n_saved_++];
  pointer = &p;
  assign_in_place(old, *slot);
  assign_in_place(*slot, value);
  return true;
}

void SweepCaseDocument::restore() {
  if (fresh_) {
    doc_ = sweep_->base;
    fresh_ = false;
  } else {
    // Last set first: a pointer set twice (or inside a value set before it) gets back its base value.
    for (std::size_t k = n_saved_; k-- > 0;) assign_in_place(doc_.at(*saved_[k].first), saved_[k].second);
  }
  n_saved_ = 0;
}

const json& SweepCaseDocument::apply(std::size_t index) {
  restore();
  bool in_place = true;
  auto set_all = [&](const std::vector<json::json_pointer>& pointers, const json& value) {
    for (const auto& p : pointers)
      if (in_place) in_place = set(p, value);
  };
  if (!sweep_->grid.empty()) {
    for (std::size_t a = 0; a < sweep_->grid.size() && in_place; ++a) {
      const auto& axis = sweep_->grid[a];
      if (!axis.patches.empty()) in_place = false;
      else set_all(axis.pointers, axis.values[sweep_->grid_value(index, a)]);
    }
  } else {
    for (const auto& c : sweep_->list[index].changes) {
      if (!c.patch.is_null()) in_place = false;
      else set_all(c.pointers, c.value);
    }
  }
  if (!in_place) {
    restore();
    doc_ = sweep_->document(index);
    fresh_ = true;
  }
  return doc_;
}

namespace {

// A case; `documents`, `models` and `reports` (each may be null: fresh ones) are the calling
// worker's, reused case after case.
void run_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir,
              SweepCaseDocument* documents, ModelBuffer* models, RunReport* reports, SweepCaseResult& r) {
  const auto t0 = std::chrono::steady_clock::now();
  r.status = SweepCaseResult::Status::Ok;
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

}  // namespace beamfea
