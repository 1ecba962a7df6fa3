#pragma once
// A JSON document changed in place and put back: values set at JSON pointers and JSON Patches
// (RFC 6902), each change recorded with its inverse, so that a sweep's worker (and the sweep's
// reader, checking each case's patch) keeps one copy of the base model instead of copying it per
// case.
//
// - A value set at a pointer (and a patch's "replace", or "add" over an existing member) is
//   written over the value it replaces where their shapes agree (numbers, strings, arrays of the
//   same length: a new pose's coordinates); the value replaced goes into a slot that is reused
//   change after change, so a warm sweep case allocates nothing.
// - "add" of a new member or array element, "remove", "move", "copy" and "test" are their
//   operations on the one container they touch (a new member allocates its node; nothing else is
//   copied).
// - What does not apply in place returns false: a pointer the document lacks, a failed "test", a
//   patch of the whole document, a malformed patch, "add" under a null. The caller puts the
//   document back (restore) and applies the change to a fresh copy, with nlohmann's patch_inplace,
//   which names the error (or, for the rare forms left to it, applies them).
//
// The pointers and the patches passed in are the caller's: they must outlive the changes made with
// them (until restore()), and a patch is parsed once and remembered by its address until
// forget_patches().
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace beamfea {

class EditableDocument {
 public:
  using json = nlohmann::json;
  using Pointer = json::json_pointer;

  explicit EditableDocument(json doc) : doc_(std::move(doc)) {}

  const json& doc() const { return doc_; }
  // Replaces the whole document (forgets the changes recorded: nothing is put back).
  void reset(json doc);

  // Sets the value at `p` (false: `p` is not in the document; nothing changed).
  bool set(const Pointer& p, const json& value);
  // Applies an RFC 6902 patch (false: it does not apply in place; the operations before the one
  // that did not are recorded, and restore() puts them back). Throws nothing of its own.
  bool patch(const json& patch);
  // The number of changes recorded so far (a mark for restore).
  std::size_t changes() const { return n_undo_; }
  // Puts back the changes after the first `mark` (all of them by default), last first.
  void restore(std::size_t mark = 0);
  // Forgets the patches parsed so far (their addresses may be reused).
  void forget_patches() { patches_.clear(); }

 private:
  // One operation of a patch, its pointers parsed, each also as (parent, last token).
  struct PatchOp {
    enum class Kind { Add, Remove, Replace, Move, Copy, Test } kind = Kind::Add;
    Pointer path, path_parent;
    std::string path_last;
    Pointer from, from_parent;
    std::string from_last;
    const json* value = nullptr;  // the operation's "value", in the caller's patch
  };
  // One change to put back.
  struct Undo {
    enum class Kind { Assign, EraseKey, EraseIndex, InsertKey, InsertIndex } kind = Kind::Assign;
    const Pointer* at = nullptr;       // Assign: the value's pointer; the others: its container's
    const std::string* key = nullptr;  // EraseKey, InsertKey
    std::size_t index = 0;             // EraseIndex, InsertIndex
    json value;                        // Assign: the value replaced; Insert*: the value removed
  };

  static std::optional<std::vector<PatchOp>> parse(const json& patch);
  bool apply(const PatchOp& op);
  bool add(const Pointer& parent, const std::string& last, const Pointer& path, const json& value);
  bool remove(const Pointer& parent, const std::string& last);
  Undo& push_undo(Undo::Kind kind, const Pointer* at);

  json doc_;
  // The changes to put back: the first n_undo_ entries; the others are spare slots whose storage
  // the next changes' values take.
  std::vector<Undo> undo_;
  std::size_t n_undo_ = 0;
  // Each patch seen, keyed by its address; an empty optional: the patch is left to a fresh copy.
  std::unordered_map<const json*, std::optional<std::vector<PatchOp>>> patches_;
};

}  // namespace beamfea
