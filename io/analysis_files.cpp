// Output file names of the analyses, and the check that no two analyses of one model can write a
// file of one name (io/analysis.hpp: AnalysisFiles, check_file_clashes).
#include <cctype>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/json_util.hpp"

namespace beamfea {

namespace {

constexpr const char* kNumberedSuffix = ".vtu";

// k as fmt writes it: digits, no leading zero (except "0" itself).
bool is_number_text(const std::string& s) {
  if (s.empty() || (s.size() > 1 && s[0] == '0')) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Is `name` one of the family "<stem><k>.vtu"?
bool in_family(const std::string& name, const std::string& stem) {
  const std::string suffix = kNumberedSuffix;
  if (name.size() <= stem.size() + suffix.size() || name.rfind(stem, 0) != 0 || !ends_with(name, suffix)) return false;
  return is_number_text(name.substr(stem.size(), name.size() - stem.size() - suffix.size()));
}

// A file name the two analyses' files share, or "" when none can. Two families "<s1><k>.vtu" and
// "<s2><k>.vtu" share a name only when s1 == s2: the stems end in a non-digit, so the number is
// the whole run of digits before ".vtu" in either reading.
std::string shared_name(const AnalysisFiles& a, const AnalysisFiles& b) {
  for (const auto& x : a.names) {
    for (const auto& y : b.names)
      if (x == y) return x;
    for (const auto& s : b.numbered_vtu_stems)
      if (in_family(x, s)) return x;
  }
  for (const auto& s : a.numbered_vtu_stems) {
    for (const auto& y : b.names)
      if (in_family(y, s)) return y;
    for (const auto& t : b.numbered_vtu_stems)
      if (s == t) return s + "<k>" + kNumberedSuffix;
  }
  return "";
}

}  // namespace

void check_file_clashes(const std::vector<AnalysisFileOwner>& analyses) {
  std::vector<AnalysisFiles> files;
  files.reserve(analyses.size());
  for (const auto& a : analyses) {
    files.push_back(a.type && a.type->files ? a.type->files(a.id) : AnalysisFiles{});
    for (const auto& s : files.back().numbered_vtu_stems)
      if (s.empty() || std::isdigit(static_cast<unsigned char>(s.back())))
        throw Error("analysis type '" + a.type->name + "': a numbered file stem must end in a non-digit");
  }
  for (std::size_t j = 0; j < analyses.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const std::string name = shared_name(files[i], files[j]);
      if (name.empty()) continue;
      throw InputError(json_in::child(analyses[j].pointer, "id"),
                       "analysis '" + analyses[j].id + "' (" + analyses[j].type->name + ") and analysis '" +
                           analyses[i].id + "' at " + json_in::child(analyses[i].pointer, "id").str() + " (" +
                           analyses[i].type->name + ") would both write '" + name +
                           "' into the output folder: rename one of them");
    }
  }
}

}  // namespace beamfea
