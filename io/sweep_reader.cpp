#include "io/sweep.hpp"

// The sweep file: reading and checking it (axes, cases, patches, outputs) and the documents of
// its cases. One case runs in io/sweep.cpp, the table is io/sweep_table.cpp, the loop app/.
#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"

namespace beamfea {

using json = nlohmann::json;
using json_in::child;

namespace {

// ---------------------------------------------------------------------------------------------
// Reading the sweep file

const char* kind_name(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "a number";
  }
}

// A value may replace another of the same kind: numbers of any representation, arrays of the
// same length whose elements are of the same kinds, any object for an object.
bool same_kind(const json& base, const json& v) {
  if (base.is_number()) return v.is_number();
  if (base.is_array()) {
    if (!v.is_array() || v.size() != base.size()) return false;
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!same_kind(base[i], v[i])) return false;
    return true;
  }
  return base.type() == v.type();
}

json::json_pointer read_pointer(const json& v, const std::string& where) {
  if (!v.is_string()) throw InputError(where, "expected a JSON pointer (a string such as \"/nodes/1/xyz\")");
  try {
    return json::json_pointer(v.get<std::string>());
  } catch (const json::exception& e) {
    throw InputError(where, "invalid JSON pointer '" + v.get<std::string>() + "': " + e.what());
  }
}

// A pointer must name an existing value of the base model.
void check_exists(const json& base, const json::json_pointer& p, const std::string& where) {
  bool exists = false;
  try {
    exists = base.contains(p);
  } catch (const json::exception&) {
    // nlohmann throws (out_of_range.404) for an array index too large for an integer: a value
    // that does not exist like any other.
  }
  if (!exists) throw InputError(where, "'" + p.to_string() + "' does not exist in the base model");
}

void check_value(const json& base, const json::json_pointer& p, const json& v, const std::string& where) {
  const json& old = base.at(p);
  if (!same_kind(old, v)) {
    std::string expected = kind_name(old);
    if (old.is_array()) expected = "an array of " + std::to_string(old.size()) + " like " + old.dump();
    throw InputError(where, "wrong type for '" + p.to_string() + "': expected " + expected + " as in the base model, got " +
                                v.dump());
  }
}

// A patch must apply to `base` (the base model, with a list case's "set" changes): it is applied in
// place and put back, and only where that fails, to a copy, which names the error.
void check_patch(EditableDocument& base, const json& patch, const std::string& where) {
  if (!patch.is_array()) throw InputError(where, "a JSON Patch must be an array of operations");
  for (std::size_t k = 0; k < patch.size(); ++k) {
    const auto& op = patch[k];
    if (!op.is_object() || !op.contains("op") || !op.contains("path"))
      throw InputError(child(where, k), "a JSON Patch operation needs \"op\" and \"path\"");
    json_in::expect_keys(op, child(where, k), {"op", "path", "value", "from"});
    // Type check for a plain replacement of an existing value, as for "set".
    if (op["op"] == "replace" && op.contains("value") && op["path"].is_string()) {
      const auto p = read_pointer(op["path"], child(child(where, k), "path"));
      check_exists(base.doc(), p, child(child(where, k), "path"));
      check_value(base.doc(), p, op["value"], child(child(where, k), "value"));
    }
  }
  const std::size_t mark = base.changes();
  const bool applied = base.patch(patch);
  base.restore(mark);
  base.forget_patches();
  if (applied) return;
  try {
    json copy = base.doc();
    copy.patch_inplace(patch);
  } catch (const json::exception& e) {
    throw InputError(where, std::string("the JSON Patch does not apply to the base model: ") + e.what());
  }
}

std::vector<json::json_pointer> read_pointers(const json& base, const json& v, const std::string& where) {
  std::vector<json::json_pointer> out;
  if (v.is_array()) {
    if (v.empty()) throw InputError(where, "no pointers");
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(read_pointer(v[i], child(where, i)));
    for (std::size_t i = 0; i < v.size(); ++i) check_exists(base, out[i], child(where, i));
  } else {
    out.push_back(read_pointer(v, where));
    check_exists(base, out[0], where);
  }
  return out;
}

SweepOutput read_output(const json& v, const std::string& where) {
  SweepOutput o;
  std::string path;
  if (v.is_string()) {
    path = v.get<std::string>();
    o.name = path;
  } else if (v.is_object()) {
    json_in::expect_keys(v, where, {"name", "path"});
    path = json_in::string(json_in::require(v, where, "path", "output"), child(where, "path"), "output path");
    o.name = v.contains("name") ? json_in::string(v["name"], child(where, "name"), "output name") : path;
  } else {
    throw InputError(where, "an output is a path string or {\"name\": ..., \"path\": ...}");
  }
  if (path.empty()) throw InputError(where, "empty output path");
  if (path[0] == '/') {
    read_pointer(json(path), where);  // validates the syntax
    std::size_t start = 1;
    for (;;) {
      const auto slash = path.find('/', start);
      const std::string raw = path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
      std::string t;  // RFC 6901 unescaping: ~1 is '/', ~0 is '~'
      for (std::size_t k = 0; k < raw.size(); ++k) {
        if (raw[k] == '~' && k + 1 < raw.size()) t += raw[++k] == '1' ? '/' : '~';
        else t += raw[k];
      }
      o.path.push_back({t, -1});
      if (slash == std::string::npos) break;
      start = slash + 1;
    }
    return o;
  }
  // Dotted form: key.key[3][0].key
  std::size_t i = 0;
  std::string key;
  auto flush_key = [&] {
    if (!key.empty()) o.path.push_back({key, -1});
    key.clear();
  };
  while (i < path.size()) {
    const char c = path[i];
    if (c == '.') {
      flush_key();
      ++i;
    } else if (c == '[') {
      flush_key();
      const auto close = path.find(']', i);
      const std::string digits = close == std::string::npos ? "" : path.substr(i + 1, close - i - 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(where, "output path '" + path + "': expected [index] at character " + std::to_string(i));
      if (digits.size() > SweepOutput::kMaxIndexDigits)
        throw InputError(where, "output path '" + path + "': index " + digits + " is out of range");
      o.path.push_back({"", std::stol(digits)});
      i = close + 1;
    } else {
      key += c;
      ++i;
    }
  }
  flush_key();
  return o;
}
}  // namespace

std::size_t Sweep::size() const {
  if (grid.empty()) return list.size();
  std::size_t n = 1;
  for (const auto& a : grid) n *= a.values.size();
  return n;
}

std::string Sweep::case_id(std::size_t index) const {
  return grid.empty() ? list[index].id : std::to_string(index);
}

namespace {
// Per-axis value indices of grid case `index`, last axis fastest.
std::vector<std::size_t> grid_indices(const std::vector<SweepAxis>& grid, std::size_t index) {
  std::vector<std::size_t> k(grid.size());
  for (std::size_t a = grid.size(); a-- > 0;) {
    k[a] = index % grid[a].values.size();
    index /= grid[a].values.size();
  }
  return k;
}
}  // namespace

std::vector<json> Sweep::parameters(std::size_t index) const {
  std::vector<json> out;
  out.reserve(parameter_names.size());
  for (std::size_t k = 0; k < parameter_names.size(); ++k) out.push_back(parameter(index, k));
  return out;
}

const json& Sweep::parameter(std::size_t index, std::size_t k) const {
  if (!grid.empty()) return grid[k].values[grid_value(index, k)];
  static const json none;
  const auto& c = list[index];
  auto it = c.parameters.find(parameter_names[k]);
  return it == c.parameters.end() ? none : *it;
}

std::vector<SweepChange> Sweep::changes(std::size_t index) const {
  if (grid.empty()) return list[index].changes;
  std::vector<SweepChange> out;
  const auto k = grid_indices(grid, index);
  for (std::size_t a = 0; a < grid.size(); ++a) {
    SweepChange c;
    if (grid[a].patches.empty()) {
      c.pointers = grid[a].pointers;
      c.value = grid[a].values[k[a]];
    } else {
      c.patch = grid[a].patches[k[a]];
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::size_t Sweep::grid_value(std::size_t index, std::size_t axis) const {
  for (std::size_t a = grid.size(); a-- > axis + 1;) index /= grid[a].values.size();
  return index % grid[axis].values.size();
}

json Sweep::document(std::size_t index) const {
  json doc = base;
  for (const auto& c : changes(index)) {
    try {
      if (c.patch.is_null())
        for (const auto& p : c.pointers) doc[p] = c.value;
      else
        doc.patch_inplace(c.patch);
    } catch (const json::exception& e) {
      throw InputError("", std::string("cannot apply the case's changes: ") + e.what());
    }
  }
  return doc;
}

namespace {

// The base model, parsed once and checked: "base" names a file (relative to `directory`), or
// "model" holds it inline.
void read_base(const json& doc, const std::filesystem::path& directory, Sweep& s) {
  if (doc.contains("base") == doc.contains("model"))
    throw InputError("/base", "name the base model: \"base\": \"model.json\" (or an inline \"model\": {...}), not both");
  if (doc.contains("base")) {
    const std::string file = json_in::string(doc["base"], "/base", "base model file");
    s.base_path = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : directory / file;
    try {
      s.base = read_json_file(s.base_path.string());
    } catch (const InputError& e) {
      throw InputError("/base", e.what());
    }
  } else {
    s.base = json_in::object(doc["model"], "/model", "inline base model");
  }
  const std::string base_ptr = doc.contains("base") ? "/base" : "/model";
  try {
    load_and_check(s.base);
  } catch (const Error& e) {
    throw InputError(base_ptr, std::string("the base model is invalid: ") + e.what());
  }
}

// The base, changed in place to check each patch and put back (one copy, made at the first patch).
class PatchChecker {
 public:
  explicit PatchChecker(const json& base) : base_(base) {}
  EditableDocument& editable() { return edits_ ? *edits_ : edits_.emplace(base_); }

 private:
  const json& base_;
  std::optional<EditableDocument> edits_;
};

// One axis of a grid, at `p`: a pointer with values, or patches with optional labels.
SweepAxis read_grid_axis(const json& value, const json_in::Pointer& p, const json& base, PatchChecker& patches) {
  const auto& ax = json_in::object(value, p, "grid axis");
  json_in::expect_keys(ax, p, {"name", "pointer", "values", "patches"});
  SweepAxis axis;
  if (ax.contains("patches")) {
    if (ax.contains("pointer")) throw InputError(child(p, "pointer"), "a grid axis has \"pointer\" or \"patches\", not both");
    const auto& ps = json_in::array(ax["patches"], child(p, "patches"), "grid axis patches");
    if (ps.empty()) throw InputError(child(p, "patches"), "empty grid axis: no patches");
    for (std::size_t k = 0; k < ps.size(); ++k) {
      check_patch(patches.editable(), ps[k], child(child(p, "patches"), k));
      axis.patches.push_back(ps[k]);
    }
    if (ax.contains("values")) {
      const auto& vs = json_in::array(ax["values"], child(p, "values"), "grid axis values");
      if (vs.size() != ps.size())
        throw InputError(child(p, "values"), "expected one value (label) per patch: " + std::to_string(ps.size()));
      axis.values.assign(vs.begin(), vs.end());
    } else {
      for (std::size_t k = 0; k < ps.size(); ++k) axis.values.emplace_back(k);
    }
    if (!ax.contains("name")) throw InputError(child(p, "name"), "a grid axis of patches needs a \"name\"");
  } else {
    axis.pointers = read_pointers(base, json_in::require(ax, p, "pointer", "grid axis"), child(p, "pointer"));
    const auto& vs = json_in::array(json_in::require(ax, p, "values", "grid axis"), child(p, "values"), "grid axis values");
    if (vs.empty()) throw InputError(child(p, "values"), "empty grid axis: no values");
    for (std::size_t k = 0; k < vs.size(); ++k) {
      for (const auto& ptr : axis.pointers) check_value(base, ptr, vs[k], child(child(p, "values"), k));
      axis.values.push_back(vs[k]);
    }
  }
  axis.name = ax.contains("name") ? json_in::string(ax["name"], child(p, "name"), "grid axis name")
                                  : axis.pointers.front().to_string();
  return axis;
}

void read_grid(const json& doc, Sweep& s, PatchChecker& patches) {
  const auto& g = json_in::array(doc["grid"], "/grid", "grid");
  if (g.empty()) throw InputError("/grid", "empty grid: no axes");
  long double n = 1;
  for (std::size_t a = 0; a < g.size(); ++a) {
    const json_in::Pointer p = child("/grid", a);
    SweepAxis axis = read_grid_axis(g[a], p, s.base, patches);
    n *= axis.values.size();
    if (n > 1e9) throw InputError(p, "the grid has more than 1e9 cases");
    s.parameter_names.push_back(axis.name);
    s.grid.push_back(std::move(axis));
  }
}

// Case i of a "cases" list, at `p`; `ids` collects the ids so far (they must differ).
SweepListCase read_list_case(const json& value, std::size_t i, const json_in::Pointer& p, const json& base,
                             PatchChecker& patches, std::set<std::string>& ids) {
  const auto& c = json_in::object(value, p, "case");
  json_in::expect_keys(c, p, {"id", "parameters", "set", "patch"});
  SweepListCase lc;
  lc.id = c.contains("id") ? json_in::id(c["id"], child(p, "id"), "case") : std::to_string(i);
  if (lc.id.empty() || lc.id == "." || lc.id == ".." ||
      lc.id.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.+-=") != std::string::npos)
    throw InputError(child(p, "id"), "case id '" + lc.id + "': use letters, digits and _ . + - = only (it names a folder)");
  if (!ids.insert(lc.id).second) throw InputError(child(p, "id"), "duplicate case id '" + lc.id + "'");
  json implicit_parameters = json::object();
  if (c.contains("set")) {
    const auto& set = json_in::object(c["set"], child(p, "set"), "case set");
    for (const auto& [k, v] : set.items()) {
      const json_in::Pointer where = child(child(p, "set"), k);
      const auto ptr = read_pointer(json(k), where);
      check_exists(base, ptr, where);
      check_value(base, ptr, v, where);
      lc.changes.push_back({{ptr}, v, json()});
      implicit_parameters[k] = v;
    }
  }
  if (c.contains("patch")) {
    // Checked on the base with this case's "set" changes applied (each pointer exists: checked above).
    EditableDocument& b = patches.editable();
    for (const auto& ch : lc.changes) b.set(ch.pointers[0], ch.value);
    check_patch(b, c["patch"], child(p, "patch"));
    b.restore();
    lc.changes.push_back({{}, json(), c["patch"]});
  }
  lc.parameters = c.contains("parameters") ? json_in::object(c["parameters"], child(p, "parameters"), "case parameters")
                                           : implicit_parameters;
  return lc;
}

void read_list(const json& doc, Sweep& s, PatchChecker& patches) {
  const auto& cs = json_in::array(doc["cases"], "/cases", "cases");
  if (cs.empty()) throw InputError("/cases", "empty list of cases");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < cs.size(); ++i) {
    SweepListCase lc = read_list_case(cs[i], i, child("/cases", i), s.base, patches, ids);
    for (const auto& [k, v] : lc.parameters.items())
      if (std::find(s.parameter_names.begin(), s.parameter_names.end(), k) == s.parameter_names.end())
        s.parameter_names.push_back(k);
    s.list.push_back(std::move(lc));
  }
}

// "analyses": the ids of the base model's analyses to run (all where absent).
void read_analyses(const json& doc, const std::set<std::string>& analysis_ids, Sweep& s) {
  if (!doc.contains("analyses")) return;
  const auto& as = json_in::array(doc["analyses"], "/analyses", "analyses");
  for (std::size_t i = 0; i < as.size(); ++i) {
    const std::string id = json_in::id(as[i], child("/analyses", i), "analysis id");
    if (!analysis_ids.count(id)) throw InputError(child("/analyses", i), "no analysis '" + id + "' in the base model");
    s.analyses.push_back(id);
  }
}

// "outputs": paths into the results, each starting at 'analyses.<id>' (one that runs), 'model' or
// 'pose' (a posed model's joint coordinates and node positions).
void read_outputs(const json& doc, const std::set<std::string>& analysis_ids, Sweep& s) {
  if (!doc.contains("outputs")) return;
  const auto& os = json_in::array(doc["outputs"], "/outputs", "outputs");
  for (std::size_t i = 0; i < os.size(); ++i) {
    const json_in::Pointer p = child("/outputs", i);
    SweepOutput o = read_output(os[i], p);
    const auto& t = o.path;
    if (t.empty() || (t[0].key != "analyses" && t[0].key != "model" && t[0].key != "pose"))
      throw InputError(p, "output '" + o.name + "': a path into the results starts with 'analyses.<id>', 'model' or 'pose'");
    if (t[0].key == "analyses") {
      if (t.size() < 2 || !analysis_ids.count(t[1].key)) {
        std::string known;
        for (const auto& a : analysis_ids) known += (known.empty() ? "" : ", ") + a;
        throw InputError(p, "output '" + o.name + "': no analysis '" + (t.size() < 2 ? "" : t[1].key) +
                                "' in the base model (analyses: " + known + ")");
      }
      if (!s.analyses.empty() && std::find(s.analyses.begin(), s.analyses.end(), t[1].key) == s.analyses.end())
        throw InputError(p, "output '" + o.name + "': analysis '" + t[1].key + "' is not among \"analyses\"");
    }
    s.outputs.push_back(std::move(o));
  }
}

// Column names must be unique, and one line each in the table's header (read back line by
// line by --resume): no control characters.
void check_column_names(const Sweep& s) {
  auto one_line = [](const std::string& name) {
    return std::none_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
  };
  std::set<std::string> names{"case", "status", "message", "wall_time_s"};
  for (std::size_t i = 0; i < s.parameter_names.size(); ++i)
    if (!one_line(s.parameter_names[i]))
      throw InputError(s.grid.empty() ? "/cases" : child(child("/grid", i), "name"),
                       "parameter name with a line break or another control character: it names a column of the table");
  for (std::size_t i = 0; i < s.outputs.size(); ++i)
    if (!one_line(s.outputs[i].name))
      throw InputError(child("/outputs", i), "output name with a line break or another control character: it names a column of the table");
  for (std::size_t i = 0; i < s.parameter_names.size(); ++i)
    if (!names.insert(s.parameter_names[i]).second)
      throw InputError(s.grid.empty() ? "/cases" : child(child("/grid", i), "name"),
                       "parameter name '" + s.parameter_names[i] + "' is used twice or clashes with a column");
  for (std::size_t i = 0; i < s.outputs.size(); ++i)
    if (!names.insert(s.outputs[i].name).second)
      throw InputError(child("/outputs", i), "output name '" + s.outputs[i].name + "' is used twice or clashes with a column");
}

}  // namespace

Sweep read_sweep(const json& doc, const std::filesystem::path& directory) {
  Sweep s;
  if (!doc.is_object()) throw InputError("", "a sweep must be a JSON object");
  json_in::expect_keys(doc, "", {"base", "model", "grid", "cases", "outputs", "analyses", "description", "title"});
  read_base(doc, directory, s);
  std::set<std::string> analysis_ids;
  if (auto it = s.base.find("analyses"); it != s.base.end())
    for (const auto& a : *it) analysis_ids.insert(json_in::id(a.at("id"), "", "analysis"));

  PatchChecker patches(s.base);
  if (doc.contains("grid") == doc.contains("cases"))
    throw InputError("/grid", "give the cases either as a \"grid\" or as a \"cases\" list (exactly one)");
  if (doc.contains("grid"))
    read_grid(doc, s, patches);
  else
    read_list(doc, s, patches);
  read_analyses(doc, analysis_ids, s);
  read_outputs(doc, analysis_ids, s);
  check_column_names(s);
  return s;
}

Sweep read_sweep_file(const std::string& path) {
  const json doc = read_json_file(path);
  return read_sweep(doc, std::filesystem::path(path).parent_path());
}

}  // namespace beamfea
