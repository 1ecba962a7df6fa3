#pragma once
// A JSON pointer (RFC 6901) that is rendered only when it is needed: the readers name the field
// they read by a pointer in every call, but a pointer string is wanted only for an error message
// (building one string per field read would be a quarter of a small sweep case).
//
// A Pointer is a root (an already-rendered pointer: "" for the document, "/nodes", or a pointer
// string held by the caller) and up to kMaxSegments keys or indices below it, stored by value:
// copying a Pointer copies its segments, so a Pointer never refers to another Pointer and a child
// of a temporary is safe to keep. It views, and does not own:
//   - its root text (a string literal, or a std::string that must outlive the Pointer: a
//     temporary std::string is refused at compile time),
//   - the keys of its segments (string literals, keys of the JSON document being read, or
//     std::strings that outlive the Pointer; a temporary std::string is refused at compile time).
// Deeper pointers than kMaxSegments below the root are rendered once into a shared, immutable
// string that the Pointer and its copies own.
#include <concepts>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

namespace beamfea::json_in {

// A temporary std::string: a key or root that would die at the end of the statement.
template <class S>
concept TemporaryString = std::same_as<std::remove_cvref_t<S>, std::string> && std::is_rvalue_reference_v<S&&>;

class Pointer {
 public:
  static constexpr int kMaxSegments = 8;

  Pointer() = default;  // the document itself: ""
  Pointer(const char* rendered) : root_(rendered) {}
  Pointer(const std::string& rendered) : root_(rendered) {}
  Pointer(std::string&&) = delete;  // would view a string that dies at the end of the statement
  // A child is made by copying its parent: the segments are copied whole (a fixed block of
  // kMaxSegments, moved by a few vector loads and stores, cheaper than a loop over those in use).
  Pointer(const Pointer&) = default;
  Pointer& operator=(const Pointer&) = default;

  Pointer child(std::string_view key) const { return pushed({key.data(), key.size()}); }
  Pointer child(std::size_t index) const { return pushed({kIndex, index}); }
  template <class S>
    requires TemporaryString<S>
  Pointer child(S&&) const = delete;

  // The RFC 6901 text: the root, then "/" and each key (with '~' written "~0" and '/' "~1") or
  // index in decimal.
  std::string str() const;
  operator std::string() const { return str(); }

 private:
  struct Segment {
    const char* key;    // kIndex: an array index
    std::size_t value;  // the key's length, or the index
  };
  static const char kIndex[];
  void append(Segment s, std::string& out) const;
  Pointer pushed(Segment s) const {
    if (count_ == kMaxSegments) return overflowed(s);
    Pointer p = *this;
    p.segments_[p.count_++] = s;
    return p;
  }
  Pointer overflowed(Segment s) const;

  std::string_view root_;
  Segment segments_[kMaxSegments]{};  // the first count_ are in use; the others zero
  int count_ = 0;
  std::shared_ptr<const std::string> owned_root_;  // set only past kMaxSegments; root_ views it
};

// Appends a key or index to a pointer, escaping per RFC 6901 (rendered when converted to a string).
inline Pointer child(const Pointer& pointer, std::string_view key) { return pointer.child(key); }
inline Pointer child(const Pointer& pointer, std::size_t index) { return pointer.child(index); }
template <class S>
  requires TemporaryString<S>
Pointer child(const Pointer& pointer, S&& key) = delete;

}  // namespace beamfea::json_in
