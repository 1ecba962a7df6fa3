#include "io/json_pointer.hpp"

namespace beamfea::json_in {

// The key of an index segment: an address no key (a view of the caller's text) can have.
const char Pointer::kIndex[] = "";

void Pointer::append(Segment s, std::string& out) const {
  out += '/';
  if (s.key == kIndex) {
    out += std::to_string(s.value);
    return;
  }
  for (std::size_t i = 0; i < s.value; ++i) {
    const char c = s.key[i];
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
}

std::string Pointer::str() const {
  std::string out(root_);
  for (int i = 0; i < count_; ++i) append(segments_[i], out);
  return out;
}

Pointer Pointer::overflowed(Segment s) const {
  // Full: render everything into a new root that the result (and its copies) own.
  Pointer p = *this;
  std::string text = str();
  append(s, text);
  p.owned_root_ = std::make_shared<const std::string>(std::move(text));
  p.root_ = *p.owned_root_;
  p.count_ = 0;
  return p;
}

}  // namespace beamfea::json_in
