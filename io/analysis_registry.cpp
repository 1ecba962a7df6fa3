#include <cmath>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/json_util.hpp"
#include "solvers/nonlinear_structure.hpp"
#include "io/load_reader.hpp"

namespace beamfea {

const std::vector<AnalysisType>& analysis_types() {
  static const std::vector<AnalysisType> types = {
      linear_static_analysis(),
      stiffness_analysis(),
      actuator_allocation_analysis(),
      buckling_analysis(),
      path_analysis(),
      modal_analysis(),
      second_order_analysis(),
      superelement_analysis(),
      frf_analysis(),
      transient_analysis(),
  };
  return types;
}

const AnalysisType* find_analysis_type(const std::string& name) {
  for (const auto& t : analysis_types())
    if (t.name == name) return &t;
  return nullptr;
}

std::string analysis_id(const nlohmann::json& v, const json_in::Pointer& pointer) {
  const std::string id = json_in::id(v, pointer, "analysis");
  if (id.size() > kMaxAnalysisIdLength)
    throw InputError(pointer, "analysis id of " + std::to_string(id.size()) + " characters: at most " +
                                  std::to_string(kMaxAnalysisIdLength) + " (it names the analysis's files)");
  if (id == "." || id == ".." ||
      id.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.+=") != std::string::npos)
    throw InputError(pointer, "analysis id '" + id + "': use letters, digits and _ - . + = only (it names the analysis's files)");
  return id;
}

void check_analyses(const Model& model, const nlohmann::json& document) {
  auto it = document.find("analyses");
  if (it == document.end()) throw InputError("/analyses", "no analyses: nothing to run (add \"analyses\": [{\"id\": ..., \"type\": ...}])");
  json_in::array(*it, "/analyses", "analyses");
  if (it->empty()) throw InputError("/analyses", "no analyses: nothing to run");
  // Two analyses or more: their ids and files must differ (owners[i] is analysis i). One cannot
  // clash with itself (and a single analysis, a sweep case's usual document, allocates nothing
  // here). Both checks compare pairs, as check_file_clashes does.
  const bool several = it->size() > 1;
  std::vector<AnalysisFileOwner> owners;
  if (several) owners.reserve(it->size());
  for (std::size_t i = 0; i < it->size(); ++i) {
    const json_in::Pointer p = json_in::child("/analyses", i);
    const auto& a = json_in::object((*it)[i], p, "analysis");
    const std::string id = analysis_id(json_in::require(a, p, "id", "analysis"), json_in::child(p, "id"));
    for (std::size_t first = 0; first < owners.size(); ++first)
      if (owners[first].id == id)
        throw InputError(json_in::child(p, "id"), "duplicate analysis id '" + id + "' (first at " +
                                                      json_in::child("/analyses", first).str() + ")");
    const std::string type = json_in::string(json_in::require(a, p, "type", "analysis '" + id + "'"),
                                             json_in::child(p, "type"), "analysis '" + id + "'");
    const AnalysisType* t = find_analysis_type(type);
    if (!t) {
      std::string known;
      for (const auto& x : analysis_types()) known += (known.empty() ? "" : ", ") + x.name;
      throw InputError(json_in::child(p, "type"), "analysis '" + id + "': unknown type '" + type + "' (known: " + known + ")");
    }
    t->check(model, a, p);
    if (several) owners.push_back({id, p, t});
  }
  if (several) check_file_clashes(owners);
}

void check_nonlinear_model(const Model& model, const json_in::Pointer& p) {
  try {
    const NonlinearStructure ns(model);
  } catch (const ModelError& e) {
    throw InputError(p, std::string("this analysis cannot run on this model: ") + e.what());
  }
}

const char* to_string(AnalysisTermination t) {
  switch (t) {
    case AnalysisTermination::Succeeded: return "succeeded";
    case AnalysisTermination::Mechanism: return "mechanism";
    case AnalysisTermination::NotConverged: return "not converged";
    case AnalysisTermination::NonFiniteResult: return "non-finite result";
    case AnalysisTermination::Failed: return "failed";
  }
  return "?";
}

std::string AnalysisOutcome::brief_report() const { return std::string(to_string(termination)) + ": " + message; }

namespace {
// Over the containers themselves (ordered_json's iterators cost several times more per value),
// the numbers of an array checked in its loop: a call per value made the check a tenth of a small
// model's analysis. Only containers and placeholders (binary values) are descended into.
bool all_finite(const ojson& v, const DeferredParts* deferred) {
  const auto finite = [&](const ojson& x) {
    if (const double* d = x.get_ptr<const double*>()) return std::isfinite(*d);
    return !(x.is_structured() || x.is_binary()) || all_finite(x, deferred);
  };
  if (const double* d = v.get_ptr<const double*>()) return std::isfinite(*d);
  if (v.is_array()) {
    for (const auto& x : v.get_ref<const ojson::array_t&>())
      if (!finite(x)) return false;
  } else if (v.is_object()) {
    for (const auto& [k, x] : v.get_ref<const ojson::object_t&>())
      if (!finite(x)) return false;
  } else if (const DeferredMembers* part = deferred ? deferred->find(v) : nullptr) {
    if (part->all_finite) return part->all_finite();
    bool ok = true;
    part->make(0, part->size, [&](std::string_view, const ojson& x) { ok = ok && all_finite(x, deferred); });
    return ok;
  }
  return true;
}
}  // namespace

std::string first_non_finite(const ojson& v, const std::string& path, const DeferredParts* deferred) {
  // The paths are built only when there is something to name (a result has thousands of numbers).
  if (all_finite(v, deferred)) return "";
  const auto member = [&](const std::string& key) { return path.empty() ? key : path + "." + key; };
  if (v.is_number_float()) return std::isfinite(v.get<double>()) ? "" : (path.empty() ? "(value)" : path);
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (auto r = first_non_finite(v[i], path + "[" + std::to_string(i) + "]", deferred); !r.empty()) return r;
  } else if (v.is_object()) {
    for (const auto& [k, x] : v.items())
      if (auto r = first_non_finite(x, member(k), deferred); !r.empty()) return r;
  } else if (const DeferredMembers* part = deferred ? deferred->find(v) : nullptr) {
    std::string first;
    part->make(0, part->size, [&](std::string_view k, const ojson& x) {
      if (first.empty()) first = first_non_finite(x, member(std::string(k)), deferred);
    });
    return first;
  }
  return "";
}

void append_new_key(ojson& object, const std::string& key, ojson value) {
  auto& map = object.get_ref<ojson::object_t&>();
  static_cast<ojson::object_t::Container&>(map).emplace_back(key, std::move(value));
}

ojson object_with_capacity(std::size_t n) {
  ojson o = ojson::object();
  static_cast<ojson::object_t::Container&>(o.get_ref<ojson::object_t&>()).reserve(n);
  return o;
}

ObjectFiller::ObjectFiller(ojson& object, std::size_t keys)
    : items_((object.is_object() ? object : (object = ojson::object())).get_ref<ojson::object_t&>()) {
  items_.reserve(keys);
}

ojson& ObjectFiller::slot(std::string_view key) {
  if (next_ < items_.size() && items_[next_].first == key) return items_[next_++].second;
  finish();  // a different shape from here on
  items_.emplace_back(std::string(key), ojson());
  return items_[next_++].second;
}

void ObjectFiller::finish() {
  // pop_back: ordered_json's (const key, value) pairs cannot be move-assigned, as erase would.
  while (items_.size() > next_) items_.pop_back();
}

void set_string(ojson& v, std::string_view s) {
  if (v.is_string()) v.get_ref<std::string&>().assign(s);
  else v = std::string(s);
}

ojson::array_t& set_array(ojson& v, std::size_t n) {
  if (!v.is_array()) v = ojson::array();
  auto& a = v.get_ref<ojson::array_t&>();
  a.resize(n);
  return a;
}

void set_numbers(ojson& v, const double* p, std::size_t n) {
  if (!v.is_array()) v = ojson::array();
  auto& a = v.get_ref<ojson::array_t&>();
  if (a.size() > n) a.resize(n);
  // A number written in place, without the temporary basic_json of an assignment.
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (double* x = a[i].get_ptr<double*>()) *x = p[i];
    else a[i] = p[i];
  }
  a.reserve(n);
  for (std::size_t i = a.size(); i < n; ++i) a.emplace_back(p[i]);
}

void set_matrix(ojson& v, const Mat6& m) {
  auto& rows = set_array(v, 6);
  for (int i = 0; i < 6; ++i) {
    const Vec6 row = m.row(i).transpose();
    set_numbers(rows[i], row.data(), 6);
  }
}

void set_vectors(ojson& v, const std::vector<Vec6>& vectors) {
  auto& a = set_array(v, vectors.size());
  for (std::size_t i = 0; i < vectors.size(); ++i) set_numbers(a[i], vectors[i].data(), 6);
}

void set_strings(ojson& v, const std::vector<std::string>& strings) {
  auto& a = set_array(v, strings.size());
  for (std::size_t i = 0; i < strings.size(); ++i) set_string(a[i], strings[i]);
}

namespace {
// An array of the n numbers at p, allocated once (push_back would grow it 1, 2, 4, 8).
ojson number_array(const double* p, std::size_t n) {
  ojson a = ojson::array();
  auto& v = a.get_ref<ojson::array_t&>();
  v.reserve(n);
  for (std::size_t i = 0; i < n; ++i) v.emplace_back(p[i]);
  return a;
}
}  // namespace

ojson to_json(const Vec3& v) { return number_array(v.data(), 3); }
ojson to_json(const Vec6& v) { return number_array(v.data(), 6); }
ojson to_json(const Eigen::VectorXd& v) { return number_array(v.data(), static_cast<std::size_t>(v.size())); }
ojson to_json(const Mat6& m) {
  ojson a = ojson::array();
  auto& rows = a.get_ref<ojson::array_t&>();
  rows.reserve(6);
  for (int i = 0; i < 6; ++i) rows.push_back(to_json(Vec6(m.row(i).transpose())));
  return a;
}

ojson matrix_to_json(const Eigen::MatrixXd& m) {
  ojson a = ojson::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    ojson row = ojson::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    a.push_back(row);
  }
  return a;
}

}  // namespace beamfea
