#include "io/model_reader.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader_parts.hpp"
#include "solvers/pose.hpp"

namespace beamfea {

using json = nlohmann::json;
using namespace json_in;

namespace {
// Deepest nesting of arrays and objects accepted: a model needs 4 (a joint's stiffness matrix);
// copying or printing a value nested without bound would overflow the stack.
constexpr int kMaxNesting = 64;

// nlohmann's DOM builder with the nesting limit. (A parse callback would do the same check, but
// nlohmann's callback parser scans the enclosing array for discarded values after every object,
// which made reading quadratic: 1.4 s of a 12 s run at 97,344 DOFs, docs/performance.md.)
class NestingLimitedDom : public nlohmann::detail::json_sax_dom_parser<json> {
 public:
  NestingLimitedDom(json& result, const std::string& source) : json_sax_dom_parser(result, true), source_(source) {}
  bool start_object(std::size_t n) { return open() && json_sax_dom_parser::start_object(n); }
  bool start_array(std::size_t n) { return open() && json_sax_dom_parser::start_array(n); }
  bool end_object() { --open_; return json_sax_dom_parser::end_object(); }
  bool end_array() { --open_; return json_sax_dom_parser::end_array(); }

 private:
  // A container inside more than kMaxNesting others is refused before it is built.
  bool open() {
    if (open_ > kMaxNesting)
      throw InputError("", source_ + ": malformed JSON: nested deeper than " + std::to_string(kMaxNesting) + " levels");
    ++open_;
    return true;
  }
  const std::string& source_;
  int open_ = 0;  // containers open around the current value
};
}  // namespace

json parse_json_text(const std::string& text, const std::string& source) {
  try {
    json result;
    NestingLimitedDom dom(result, source);
    json::sax_parse(text, &dom);  // strict: nothing but white space after the value
    return result;
  } catch (const json::parse_error& e) {
    throw InputError("", source + ": malformed JSON at byte " + std::to_string(e.byte) + ": " + e.what());
  } catch (const json::exception& e) {
    // A number beyond double range (1e999) is out_of_range, not parse_error: still malformed.
    throw InputError("", source + ": malformed JSON: " + e.what());
  }
}

json read_json_file(const std::string& path) {
  // Only a regular file of bounded size: a device or a pipe (/dev/zero, a FIFO) could be read
  // without end, and a file larger than kMaxInputFileBytes is no model a person wrote.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError("", "cannot read file '" + path + "': no such file");
  if (!std::filesystem::is_regular_file(status))
    throw InputError("", "cannot read '" + path + "': not a regular file (a model is read from a file, not a device, folder or pipe)");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError("", "cannot read file '" + path + "': " + ec.message());
  if (size > kMaxInputFileBytes)
    throw InputError("", "cannot read file '" + path + "': " + std::to_string(size) + " bytes, above the limit of " +
                             std::to_string(kMaxInputFileBytes) + " bytes of an input file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("", "cannot read file '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  json doc = parse_json_text(ss.str(), path);
  resolve_link_model_paths(doc, std::filesystem::path(path).parent_path());
  return doc;
}

void resolve_link_model_paths(json& doc, const std::filesystem::path& folder) {
  if (folder.empty() || !doc.is_object()) return;
  const auto joints = doc.find("joints");
  if (joints == doc.end() || !joints->is_array()) return;
  for (auto& joint : *joints) {
    if (!joint.is_object()) continue;
    const auto from = joint.find("stiffness_from_model");
    if (from == joint.end() || !from->is_object()) continue;
    const auto model = from->find("model");
    if (model == from->end() || !model->is_string()) continue;
    const std::filesystem::path p(model->get<std::string>());
    if (p.is_relative()) *model = (folder / p).lexically_normal().string();
  }
}

int node_ref(const Model& m, const json& v, const json_in::Pointer& pointer) {
  const std::string id = json_in::id(v, pointer, "node reference");
  const int n = m.find_node(id);
  if (n < 0) throw InputError(pointer, "unknown node '" + id + "'");
  return n;
}

int joint_ref(const Model& m, const json& v, const json_in::Pointer& pointer) {
  const std::string id = json_in::id(v, pointer, "joint reference");
  const int j = m.find_joint(id);
  if (j < 0) throw InputError(pointer, "unknown joint '" + id + "'");
  return j;
}

namespace reader {

const json& collection(const json& doc, const char* key, bool required) {
  static const json empty = json::array();
  auto it = doc.find(key);
  if (it == doc.end()) {
    if (required) throw InputError(std::string("/") + key, std::string("missing '") + key + "'");
    return empty;
  }
  return array(*it, Pointer().child(key), key);
}

void check_unique(int first, const std::string& kind, const Pointer& base, const std::string& id, std::size_t i) {
  if (first >= 0)
    throw InputError(child(child(base, i), "id"),
                     "duplicate " + kind + " id '" + id + "' (first at " + child(base, static_cast<std::size_t>(first)).str() + ")");
}

DofRef read_dof_target(const Model& m, const json& e, const json_in::Pointer& p, const std::string& what) {
  if (const json* joint = field(e, "joint")) {
    const int j = joint_ref(m, *joint, child(p, "joint"));
    const json* coordinate = field(e, "coordinate");
    const int c = coordinate ? integer(*coordinate, child(p, "coordinate"), what) : 0;
    if (c < 0 || c >= m.joints[j].coordinates())
      throw InputError(child(p, "coordinate"), what + ": joint '" + m.joints[j].id + "' has " +
                                                   std::to_string(m.joints[j].coordinates()) + " coordinate(s)");
    return {DofRef::Owner::Joint, j, c};
  }
  const int n = node_ref(m, require(e, p, "node", what), child(p, "node"));
  const int k = dof_name(require(e, p, "dof", what), child(p, "dof"), what, What(what, " at node '", m.nodes[n].id + "': "));
  return {DofRef::Owner::Node, n, k};
}

}  // namespace reader

namespace {

// read_model into an empty `m`, its items taking the storage of `spare`'s (may be null).
// `what`: storage for the items' names in messages (reader::ReadState::what).
void read_model_into(const json& doc, Model& m, Model* spare, std::string& what) {
  if (!doc.is_object()) throw InputError("", "the model must be a JSON object");
  // Top-level keys of a model file (docs/input-format.md). Add a new collection here.
  expect_keys(doc, "", {"nodes", "materials", "sections", "elements", "joints", "supports", "loads", "prescribed",
                        "analyses", "units", "title", "name", "description", "gravity", "masses", "load_cases",
                        "combinations", "ties", "constraints", "pose", "damping", "solver", "generate"});
  reader::ReadState s{doc, m, spare, 1.0, what};
  reader::read_nodes(s);
  s.length_scale = m.length_scale();  // meshing adds nodes on members only: the box stays the same
  reader::read_materials(s);
  reader::read_sections(s);
  reader::read_members(s);
  if (doc.contains("generate")) {
    reader::read_generate(s);
    s.length_scale = m.length_scale();  // the generated nodes widen the box
  }
  reader::read_joints(s);
  reader::read_supports(s);
  reader::read_loads(s);
  reader::read_prescribed(s);
  reader::read_ties(s);
  reader::read_constraints(s);
  reader::read_damping(s);
  reader::read_solver(s);
  reader::read_pose(s);
  pose_model(m);  // the posed geometry becomes the reference of every analysis (solvers/pose.hpp)
}

}  // namespace

Model read_model(const json& doc) {
  Model m;
  std::string what;
  read_model_into(doc, m, nullptr, what);
  return m;
}

const Model& ModelBuffer::read(const json& doc) {
  std::swap(model_, spare_);  // the last read becomes the spare
  model_.clear();             // the one before: emptied, its vectors' storage kept
  read_model_into(doc, model_, &spare_, what_);
  return model_;
}

}  // namespace beamfea
