#include "io/run.hpp"

#include <chrono>
#include <iostream>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"

namespace beamfea {

Model load_and_check(const nlohmann::json& document) {
  Model m = read_model(document);
  check_analyses(m, document);
  return m;
}

RunReport run_document(const Model& model, const nlohmann::json& document, const RunOptions& options) {
  RunReport report;
  report.results["beamfea"] = "0.1.0";
  report.results["model"] = {{"nodes", model.nodes.size()},
                             {"elements", model.elements.size()},
                             {"members", model.members.size()},
                             {"joints", model.joints.size()}};
  ojson analyses = ojson::object();
  if (!options.out_dir.empty()) std::filesystem::create_directories(options.out_dir);
  if (auto it = document.find("analyses"); it != document.end()) {
    for (std::size_t i = 0; i < it->size(); ++i) {
      const auto& spec = (*it)[i];
      const std::string id = json_in::id(spec.at("id"), "", "analysis");
      if (!options.only.empty() && std::find(options.only.begin(), options.only.end(), id) == options.only.end())
        continue;
      const AnalysisType* type = find_analysis_type(spec.at("type").get<std::string>());
      AnalysisContext ctx{model, document, spec, json_in::child("/analyses", i), id, options.out_dir, options.write_vtk, {}};
      if (options.verbose) ctx.progress = [&](const std::string& s) { std::cerr << "[" << id << "] " << s << "\n"; };
      const auto t0 = std::chrono::steady_clock::now();
      AnalysisOutcome o = type->run(ctx);
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      o.result["wall_time_s"] = dt;
      if (options.verbose) std::cerr << "[" << id << "] " << o.message << " (" << dt << " s)\n";
      report.failed = report.failed || o.failed;
      analyses[id] = std::move(o.result);
    }
  }
  report.results["analyses"] = std::move(analyses);
  if (!options.out_dir.empty())
    write_text_atomic(options.out_dir / "results.json", report.results.dump(2) + "\n");
  return report;
}

}  // namespace beamfea
