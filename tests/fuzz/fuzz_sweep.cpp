// libFuzzer target over the sweep file: parsing, read_sweep's checks, and for a few
// cases of an accepted sweep (the first, the middle and the last) the case document, one
// bounded run, and the table's header and row. Built with fuzz_model (-DBEAMFEA_BUILD_FUZZERS=ON,
// clang); how to build and run it: docs/testing.md.
//
// A "base" file name is always replaced by tests/fuzz/corpus_sweep/base.json: the fuzzer never
// reads the machine's files (a "base" of /dev/zero would only measure the disk).
//
// The rules, beside "no crash, no sanitizer report, only beamfea's errors":
// - an accepted sweep has cases, each with a case id that can be a folder name (--keep) and one
//   value per parameter column;
// - a case runs in the sweep as it runs alone: run_sweep_case's status is the exit code that
//   `beamfea run` gives for the case's document (ok 0, analysis failed 1, bad input 2);
// - the table stays readable: the header and every row are one line each that splits back into
//   the same cells, and a table's own header gives back its columns (--resume).
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "fuzz/harness.hpp"
#include "io/sweep.hpp"
#include "io/sweep_table.hpp"

namespace {

using beamfea::fuzz::broken_rule;
using nlohmann::json;

int expected_code(beamfea::SweepCaseResult::Status s) {
  switch (s) {
    case beamfea::SweepCaseResult::Status::Succeeded: return 0;
    case beamfea::SweepCaseResult::Status::AnalysisFailed: return 1;
    case beamfea::SweepCaseResult::Status::BadInput: return 2;
  }
  return -1;
}

void check_line(const std::string& line, const std::vector<std::string>& cells, const std::string& what) {
  if (line.empty() || line.back() != '\n' || line.find('\n') != line.size() - 1)
    broken_rule(what + " is not one line: " + line);
  if (beamfea::csv_split(line.substr(0, line.size() - 1)) != cells)
    broken_rule(what + " does not split back into its cells: " + line);
}

void check_case(const beamfea::Sweep& s, std::size_t i) {
  const std::string id = s.case_id(i);
  if (id.empty() || id == "." || id == ".." || id.find('/') != std::string::npos || id.find('\0') != std::string::npos)
    broken_rule("case id '" + id + "' cannot be a folder name");
  if (s.parameters(i).size() != s.parameter_names.size()) broken_rule("a case without one value per parameter column");

  // The case alone: its document, bounded, checked and run as `beamfea run` would.
  int alone = 2;
  bool comparable = true;
  try {
    const json doc = s.document(i);
    json bounded = doc;
    beamfea::fuzz::bound(bounded);
    const auto outcome = beamfea::fuzz::run_document_case(bounded, s.analyses);
    alone = outcome.code;
    // run_sweep_case runs the document as it is: compare only when bounding changed nothing and
    // the model was small enough to run.
    comparable = bounded == doc && (outcome.ran || outcome.code == 2);
  } catch (const beamfea::InputError&) {
    alone = 2;  // the case's changes do not apply: a "bad input" row
  } catch (const std::exception& e) {
    broken_rule(std::string("a case's document threw a non-beamfea exception: ") + e.what());
  }
  if (!comparable) return;
  const beamfea::SweepCaseResult r = beamfea::run_sweep_case(s, i);
  if (expected_code(r.status) != alone)
    broken_rule("case " + id + ": the sweep says '" + beamfea::to_string(r.status) + "' (" + r.message +
                "), the same document alone gives exit " + std::to_string(alone));

  // Its row in a table whose columns it settles.
  const beamfea::SweepColumns columns =
      beamfea::sweep_columns(s, r.status == beamfea::SweepCaseResult::Status::Succeeded ? &r : nullptr);
  const auto header = columns.header(s);
  check_line(beamfea::csv_line(header), header, "the header");
  const std::string row = beamfea::sweep_row(s, i, columns, r);
  if (row.find('\n') != row.size() - 1) broken_rule("a row is not one line: " + row);
  if (beamfea::csv_split(row.substr(0, row.size() - 1)).size() != header.size())
    broken_rule("a row without one cell per column: " + row);
  try {
    if (beamfea::sweep_columns_from_header(s, header, "table").outputs != columns.outputs)
      broken_rule("a table's header gives back other columns (--resume would mix them up)");
  } catch (const beamfea::InputError& e) {
    broken_rule(std::string("a table's own header is not one of its sweep: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  json doc;
  try {
    doc = beamfea::parse_json_text(text, "fuzz");
  } catch (const beamfea::InputError&) {
    return 0;
  } catch (const std::exception& e) {
    broken_rule(std::string("parsing threw a non-beamfea exception: ") + e.what());
  }
  if (doc.is_object() && doc.contains("base") && doc["base"].is_string()) doc["base"] = "base.json";
  if (doc.is_object() && doc.contains("model")) beamfea::fuzz::bound(doc["model"]);
  beamfea::Sweep s;
  try {
    s = beamfea::read_sweep(doc, BEAMFEA_FUZZ_SWEEP_DIR);
  } catch (const beamfea::InputError&) {
    return 0;
  } catch (const beamfea::ModelError&) {
    return 0;
  } catch (const std::exception& e) {
    broken_rule(std::string("reading a sweep threw a non-beamfea exception: ") + e.what());
  }
  const std::size_t n = s.size();
  if (n == 0) broken_rule("a sweep without cases was accepted");
  // Three cases at most (the first, the middle, the last): each runs twice, bounded.
  const std::set<std::size_t> picks{0, n / 2, n - 1};
  std::set<std::string> ids;
  for (std::size_t i : picks) {
    if (!ids.insert(s.case_id(i)).second) broken_rule("two cases with the id '" + s.case_id(i) + "'");
    check_case(s, i);
  }
  return 0;
}
