#include "io/editable_document.hpp"

#include <algorithm>
#include <charconv>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace beamfea {

using json = nlohmann::json;

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

// An array index token of a JSON pointer (RFC 6901 section 4: "0" or digits without a leading zero).
std::optional<std::size_t> array_index(const std::string& token) {
  if (token.empty() || token.size() > 18 || (token.size() > 1 && token[0] == '0')) return std::nullopt;
  std::size_t i = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), i);
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return i;
}

}  // namespace

void EditableDocument::reset(json doc) {
  doc_ = std::move(doc);
  n_undo_ = 0;
}

EditableDocument::Undo& EditableDocument::push_undo(Undo::Kind kind, const Pointer* at) {
  if (n_undo_ == undo_.size()) undo_.emplace_back();
  Undo& u = undo_[n_undo_++];
  u.kind = kind;
  u.at = at;
  return u;
}

bool EditableDocument::set(const Pointer& p, const json& value) {
  // One traversal: `at` throws (out_of_range, or parse_error for an index that is not one) exactly
  // where `contains` says false.
  json* slot = nullptr;
  try {
    slot = &doc_.at(p);
  } catch (const json::exception&) {
    return false;
  }
  Undo& u = push_undo(Undo::Kind::Assign, &p);
  assign_in_place(u.value, *slot);
  assign_in_place(*slot, value);
  return true;
}

// RFC 6902 section 4.1, "add" at `path` = parent + last. nlohmann's patch_inplace (what a fresh copy
// gets) does the same in every case handled here; the others return false.
bool EditableDocument::add(const Pointer& parent_ptr, const std::string& last, const Pointer& path, const json& value) {
  json& parent = doc_.at(parent_ptr);
  if (parent.is_object()) {
    if (parent.contains(last)) return set(path, value);  // an existing member is replaced
    parent.emplace(last, value);
    push_undo(Undo::Kind::EraseKey, &parent_ptr).key = &last;
    return true;
  }
  if (!parent.is_array()) return false;  // null (nlohmann makes it an object) or a scalar
  std::size_t i = parent.size();         // "-": after the last element
  if (last != "-") {
    const auto index = array_index(last);
    if (!index || *index > parent.size()) return false;
    i = *index;
  }
  parent.insert(parent.begin() + static_cast<std::ptrdiff_t>(i), value);
  push_undo(Undo::Kind::EraseIndex, &parent_ptr).index = i;
  return true;
}

// RFC 6902 section 4.2, "remove" of parent's member `last`; the removed value is kept to be put back.
bool EditableDocument::remove(const Pointer& parent_ptr, const std::string& last) {
  json& parent = doc_.at(parent_ptr);
  if (parent.is_object()) {
    const auto it = parent.find(last);
    if (it == parent.end()) return false;
    Undo& u = push_undo(Undo::Kind::InsertKey, &parent_ptr);
    u.key = &last;
    u.value = std::move(*it);
    parent.erase(it);
    return true;
  }
  if (!parent.is_array()) return false;
  const auto index = array_index(last);
  if (!index || *index >= parent.size()) return false;
  Undo& u = push_undo(Undo::Kind::InsertIndex, &parent_ptr);
  u.index = *index;
  u.value = std::move(parent[*index]);
  parent.erase(*index);
  return true;
}

bool EditableDocument::apply(const PatchOp& op) {
  using Kind = PatchOp::Kind;
  switch (op.kind) {
    case Kind::Replace: return set(op.path, *op.value);                      // section 4.3
    case Kind::Add: return add(op.path_parent, op.path_last, op.path, *op.value);
    case Kind::Remove: return remove(op.path_parent, op.path_last);
    case Kind::Test: return doc_.at(op.path) == *op.value;                   // section 4.6
    case Kind::Copy: {                                                       // section 4.5
      const json value = doc_.at(op.from);
      return add(op.path_parent, op.path_last, op.path, value);
    }
    case Kind::Move: {  // section 4.4: "remove" at "from", then "add" of the value removed
      if (!remove(op.from_parent, op.from_last)) return false;
      const json value = undo_[n_undo_ - 1].value;  // the undo entry just made holds it
      return add(op.path_parent, op.path_last, op.path, value);
    }
  }
  return false;
}

std::optional<std::vector<EditableDocument::PatchOp>> EditableDocument::parse(const json& patch) {
  static const std::pair<const char*, PatchOp::Kind> kinds[] = {
      {"add", PatchOp::Kind::Add},   {"remove", PatchOp::Kind::Remove}, {"replace", PatchOp::Kind::Replace},
      {"move", PatchOp::Kind::Move}, {"copy", PatchOp::Kind::Copy},     {"test", PatchOp::Kind::Test}};
  // Anything unusual (not an array of operations, a pointer that does not parse, the whole document
  // as the target) is left to a fresh copy.
  try {
    if (!patch.is_array()) return std::nullopt;
    std::vector<PatchOp> ops;
    for (const auto& o : patch) {
      PatchOp op;
      const auto kind =
          std::find_if(std::begin(kinds), std::end(kinds), [&](const auto& k) { return o.at("op") == k.first; });
      if (kind == std::end(kinds)) return std::nullopt;
      op.kind = kind->second;
      op.path = Pointer(o.at("path").get<std::string>());
      if (op.path.empty()) return std::nullopt;
      op.path_parent = op.path.parent_pointer();
      op.path_last = op.path.back();
      if (op.kind == PatchOp::Kind::Move || op.kind == PatchOp::Kind::Copy) {
        op.from = Pointer(o.at("from").get<std::string>());
        if (op.from.empty()) return std::nullopt;
        op.from_parent = op.from.parent_pointer();
        op.from_last = op.from.back();
      }
      if (op.kind == PatchOp::Kind::Add || op.kind == PatchOp::Kind::Replace || op.kind == PatchOp::Kind::Test)
        op.value = &o.at("value");
      ops.push_back(std::move(op));
    }
    return ops;
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

bool EditableDocument::patch(const json& patch) {
  auto found = patches_.find(&patch);
  if (found == patches_.end()) found = patches_.emplace(&patch, parse(patch)).first;
  if (!found->second) return false;
  try {
    for (const PatchOp& op : *found->second)
      if (!apply(op)) return false;
  } catch (const json::exception&) {
    return false;  // a pointer the document lacks (`at` checks before anything changes)
  }
  return true;
}

void EditableDocument::restore(std::size_t mark) {
  // Last change first: each finds the document as that change left it.
  for (std::size_t k = n_undo_; k-- > mark;) {
    Undo& u = undo_[k];
    json& at = doc_.at(*u.at);
    switch (u.kind) {
      case Undo::Kind::Assign: assign_in_place(at, u.value); break;
      case Undo::Kind::EraseKey: at.erase(*u.key); break;
      case Undo::Kind::EraseIndex: at.erase(u.index); break;
      case Undo::Kind::InsertKey: at.emplace(*u.key, std::move(u.value)); break;
      case Undo::Kind::InsertIndex: at.insert(at.begin() + static_cast<std::ptrdiff_t>(u.index), std::move(u.value)); break;
    }
  }
  n_undo_ = mark;
}

}  // namespace beamfea
