#include <set>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/json_util.hpp"

namespace beamfea {

const std::vector<AnalysisType>& analysis_types() {
  static const std::vector<AnalysisType> types = {
      linear_static_analysis(),
      stiffness_analysis(),
      actuator_allocation_analysis(),
      buckling_analysis(),
      path_analysis(),
  };
  return types;
}

const AnalysisType* find_analysis_type(const std::string& name) {
  for (const auto& t : analysis_types())
    if (t.name == name) return &t;
  return nullptr;
}

void check_analyses(const Model& model, const nlohmann::json& document) {
  auto it = document.find("analyses");
  if (it == document.end()) return;
  json_in::array(*it, "/analyses", "analyses");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const std::string p = json_in::child("/analyses", i);
    const auto& a = json_in::object((*it)[i], p, "analysis");
    const std::string id = json_in::id(json_in::require(a, p, "id", "analysis"), json_in::child(p, "id"), "analysis");
    if (!ids.insert(id).second) throw InputError(json_in::child(p, "id"), "duplicate analysis id '" + id + "'");
    const std::string type = json_in::string(json_in::require(a, p, "type", "analysis '" + id + "'"),
                                             json_in::child(p, "type"), "analysis '" + id + "'");
    const AnalysisType* t = find_analysis_type(type);
    if (!t) {
      std::string known;
      for (const auto& x : analysis_types()) known += (known.empty() ? "" : ", ") + x.name;
      throw InputError(json_in::child(p, "type"), "analysis '" + id + "': unknown type '" + type + "' (known: " + known + ")");
    }
    t->check(model, a, p);
  }
}

ojson to_json(const Vec3& v) { return ojson::array({v[0], v[1], v[2]}); }
ojson to_json(const Vec6& v) {
  ojson a = ojson::array();
  for (int i = 0; i < 6; ++i) a.push_back(v[i]);
  return a;
}
ojson to_json(const Eigen::VectorXd& v) {
  ojson a = ojson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}
ojson to_json(const Mat6& m) {
  ojson a = ojson::array();
  for (int i = 0; i < 6; ++i) a.push_back(to_json(Vec6(m.row(i).transpose())));
  return a;
}

}  // namespace beamfea
