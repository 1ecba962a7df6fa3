#include "io/json_pointer.hpp"

namespace beamfea::json_in {

void Pointer::append(Segment s, std::string& out) const {
  out += '/';
  if (s.is_index) {
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

Pointer Pointer::pushed(Segment s) const {
  Pointer p = *this;
  if (p.count_ < kMaxSegments) {
    p.segments_[p.count_++] = s;
    return p;
  }
  // Full: render everything into a new root that the result (and its copies) own.
  std::string text = str();
  append(s, text);
  p.owned_root_ = std::make_shared<const std::string>(std::move(text));
  p.root_ = *p.owned_root_;
  p.count_ = 0;
  return p;
}

Pointer Pointer::child(std::string_view key) const { return pushed({key.data(), key.size(), false}); }

Pointer Pointer::child(std::size_t index) const { return pushed({nullptr, index, true}); }

}  // namespace beamfea::json_in
