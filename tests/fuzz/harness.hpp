#pragma once
// One fuzz case: parse, check, and (for small models) a bounded run without files. Shared by the
// libFuzzer targets (fuzz_model.cpp, fuzz_sweep.cpp). Returns the exit code the program would
// give (0, 1, 2) and aborts when a rule is broken (see fuzz_model.cpp).
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"

namespace beamfea::fuzz {

// Bounds of the run part: bigger models are only parsed and checked.
inline constexpr std::size_t kMaxRunNodes = 60;
inline constexpr int kMaxRunPathSteps = 20;
inline constexpr int kMaxRunModes = 4;

[[noreturn]] inline void broken_rule(const std::string& what) {
  std::cerr << "fuzz rule broken: " << what << "\n";
  std::abort();
}

// `v` lowered to `cap` when it is a larger number (a smaller value, or a wrong type that the
// checks must reject, stays as it is).
inline void cap_at(nlohmann::json& v, int cap) {
  if (v.is_number() && !(v.get<double>() <= cap)) v = cap;
}

// Caps the costly options so that one case runs in milliseconds.
inline void bound(nlohmann::json& doc) {
  auto it = doc.find("analyses");
  if (it == doc.end() || !it->is_array()) return;
  for (auto& a : *it) {
    if (!a.is_object()) continue;
    if (a.contains("max_steps")) cap_at(a["max_steps"], kMaxRunPathSteps);
    else if (a.contains("type") && a["type"] == "path") a["max_steps"] = kMaxRunPathSteps;
    if (a.contains("modes")) cap_at(a["modes"], kMaxRunModes);
  }
}

// What one document gives: the program's exit code, and whether its analyses ran (false: too
// big, only read and checked).
struct DocumentOutcome {
  int code = 0;
  bool ran = false;
};

// Checks and (when small) runs a parsed model document, already bounded; `only`: the analysis
// ids to run (empty: all).
inline DocumentOutcome run_document_case(const nlohmann::json& doc, const std::vector<std::string>& only = {}) {
  Model model;
  try {
    model = load_and_check(doc);
  } catch (const InputError&) {
    return {2, false};
  } catch (const ModelError&) {
    return {2, false};
  } catch (const std::exception& e) {
    broken_rule(std::string("reading or checking threw a non-beamfea exception: ") + e.what());
  }
  if (model.nodes.size() > kMaxRunNodes) return {0, false};
  try {
    RunOptions opt;  // no files, no messages
    opt.only = only;
    const RunReport r = run_document(model, doc, opt);
    return {r.failed ? 1 : 0, true};
  } catch (const InputError& e) {
    // An --analysis id that the model lacks is bad input, said before anything runs.
    if (!only.empty()) return {2, false};
    broken_rule(std::string("a run after a successful check threw: ") + e.what());
  } catch (const std::exception& e) {
    broken_rule(std::string("a run after a successful check threw: ") + e.what());
  }
}

inline int run_one_case(const std::string& text) {
  nlohmann::json doc;
  try {
    doc = parse_json_text(text, "fuzz");
  } catch (const InputError&) {
    return 2;
  } catch (const std::exception& e) {
    broken_rule(std::string("parsing threw a non-beamfea exception: ") + e.what());
  }
  bound(doc);
  return run_document_case(doc).code;
}

}  // namespace beamfea::fuzz
