#include "io/actuator_load_case_output.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "solvers/scheme_ranking.hpp"

namespace beamfea {

namespace {

ojson number_or_null(double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); }
std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : std::string(); }

ojson six(const Vec6& v) {
  ojson o;
  for (int k = 0; k < 6; ++k) o[kDofNames[k]] = v[k];
  return o;
}

const LoadedSchemeModel& model_of(const SchemeLoadResponse& r, int which) {
  return which == 0 ? r.actuated : which == 1 ? r.structural : r.total;
}
constexpr const char* kModels[] = {"actuated", "structural", "total"};

}  // namespace

void write_load_response(const Model& model, const AllocationOptions& o, const std::vector<int>& scheme,
                         const SchemeLoadResponse& r, ojson& po) {
  ojson eff = ojson::array();
  for (std::size_t k = 0; k < scheme.size(); ++k) {
    const auto& c = o.candidates[scheme[k]];
    eff.push_back(ojson{{"joint", model.joints[c.joint].id},
                        {"coordinate", c.coordinate},
                        {"effort", r.efforts_ok ? ojson(r.efforts[static_cast<Eigen::Index>(k)]) : ojson(nullptr)}});
  }
  po["actuator_efforts"] = eff;
  po["actuator_efforts_message"] = r.efforts_message;
  ojson disp, msgs;
  for (int w = 0; w < 3; ++w) {
    const auto& m = model_of(r, w);
    disp[kModels[w]] = m.ok ? six(m.platform) : ojson(nullptr);
    msgs[kModels[w]] = m.message;
  }
  disp["messages"] = msgs;
  po["platform_displacement"] = disp;
  const int nd = static_cast<int>(o.directions.size());
  const auto comp = loaded_scheme_components(r, nd);
  ojson ks, kmsg, co;
  for (int w = 0; w < 3; ++w) {
    const auto& m = model_of(r, w);
    ks[kModels[w]] = m.stiffness_ok ? matrix_to_json(m.K_loaded) : ojson(nullptr);
    kmsg[kModels[w]] = m.stiffness_message;
    ojson v;
    for (int d = 0; d < nd; ++d) v[kDofNames[o.directions[d]]] = number_or_null(comp[w][d]);
    co[kModels[w]] = v;
  }
  ks["components"] = co;
  ks["messages"] = kmsg;
  po["loaded_stiffness"] = ks;
}

std::string efforts_csv_rows(const Model& model, const AllocationOptions& o, const std::vector<int>& scheme,
                             const std::string& name, const std::string& pose, const SchemeLoadResponse& r) {
  std::string s;
  for (std::size_t k = 0; k < scheme.size(); ++k) {
    const auto& c = o.candidates[scheme[k]];
    s += fmt::format("{},{},{},{},{}\n", name, pose, model.joints[c.joint].id, c.coordinate,
                     r.efforts_ok ? csv_number(r.efforts[static_cast<Eigen::Index>(k)]) : std::string());
  }
  return s;
}

std::string load_case_csv_rows(const AllocationOptions& o, const std::string& name, const std::string& pose,
                               const SchemeLoadResponse& r) {
  const int nd = static_cast<int>(o.directions.size());
  const auto comp = loaded_scheme_components(r, nd);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string s;
  for (int d = 0; d < nd; ++d) {
    const int dof = o.directions[d];
    auto u = [&](const LoadedSchemeModel& m) { return m.ok ? m.platform[dof] : nan; };
    s += fmt::format("{},{},{},{},{},{},{},{},{}\n", name, pose, kDofNames[dof], csv_number(u(r.total)),
                     csv_number(u(r.structural)), csv_number(u(r.actuated)), csv_number(comp[0][d]),
                     csv_number(comp[1][d]), csv_number(comp[2][d]));
  }
  return s;
}

}  // namespace beamfea
