#include "io/json_writer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace beamfea {

namespace {

using ojson = nlohmann::ordered_json;

// The text is built in `out`; with a stream, `out` is handed to it whenever it passes a chunk, so
// that a results.json of hundreds of megabytes never sits whole in memory.
inline constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

struct Sink {
  std::string& out;
  std::ostream* stream = nullptr;
  void flush_if_full() {
    if (stream && out.size() >= kChunkBytes) flush();
  }
  void flush() {
    stream->write(out.data(), static_cast<std::streamsize>(out.size()));
    out.clear();
  }
};

bool is_scalar(const ojson& v) { return !v.is_structured(); }

void write_string(const std::string& s, std::string& out) {
  for (const char c : s)
    if (static_cast<unsigned char>(c) >= 0x80) {
      // Non-ASCII: nlohmann's own serialiser (UTF-8 passed through, invalid UTF-8 an error).
      out += ojson(s).dump();
      return;
    }
  out += '"';
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          static constexpr char hex[] = "0123456789abcdef";
          out += "\\u00";
          out += hex[(c >> 4) & 0xf];
          out += hex[c & 0xf];
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

// The shortest round-trip text of a double, remembered. A results object repeats its numbers: a
// member's axial and shear forces and torque at every one of its stations, its end forces again
// with the sign flipped as section forces, the stations' positions along equal members. At
// 21,504 DOFs (1.14 million numbers in results.json) 68 % of them are found in a table of 256
// entries keyed by |x|, each one a look-up of a few ns where std::to_chars takes about 65 ns.
// Direct-mapped: a slot holds the last value hashed to it. One table per thread (writers may run
// on several), zero-initialised, so no guard on access: an empty slot's key ~0 is a NaN's bits,
// which no finite value has.
struct DoubleText {
  std::uint64_t not_bits;  // ~bits of |x|
  char text[31];           // |x| as written, ".0" included: at most 24 characters (to_chars writes
                           // an integer of 17 digits in fixed notation up to 22 characters long)
  std::uint8_t size;       // of text
};
inline constexpr std::size_t kDoubleTextSlots = 256;  // 64: 61 % found; 1,024: 70 % (same model)
static_assert(std::has_single_bit(kDoubleTextSlots));
thread_local std::array<DoubleText, kDoubleTextSlots> t_double_text{};

void write_double(double x, std::string& out) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  if (std::signbit(x)) out += '-';
  const double a = std::fabs(x);
  const auto bits = std::bit_cast<std::uint64_t>(a);
  // Fibonacci hashing: the top bits of the product pick the slot.
  constexpr int kShift = 64 - std::countr_zero(kDoubleTextSlots);
  DoubleText& slot = t_double_text[(bits * 0x9E3779B97F4A7C15ULL) >> kShift];
  if (slot.not_bits != ~bits) {
    const auto r = std::to_chars(slot.text, slot.text + sizeof slot.text - 2, a);  // room for ".0"
    char* end = r.ptr;
    if (std::find_if(slot.text, end, [](char c) { return c == '.' || c == 'e'; }) == end) {
      *end++ = '.';
      *end++ = '0';
    }
    slot.size = static_cast<std::uint8_t>(end - slot.text);
    slot.not_bits = ~bits;
  }
  out.append(slot.text, slot.size);
}

template <class Int>
void write_integer(Int x, std::string& out) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void write_scalar(const ojson& v, std::string& out) {
  switch (v.type()) {
    case ojson::value_t::null: out += "null"; break;
    case ojson::value_t::boolean: out += v.get_ref<const bool&>() ? "true" : "false"; break;
    case ojson::value_t::number_float: write_double(v.get_ref<const double&>(), out); break;
    case ojson::value_t::number_integer: write_integer(v.get_ref<const std::int64_t&>(), out); break;
    case ojson::value_t::number_unsigned: write_integer(v.get_ref<const std::uint64_t&>(), out); break;
    case ojson::value_t::string: write_string(v.get_ref<const std::string&>(), out); break;
    default: out += v.dump(); break;  // binary: not produced by beamfea
  }
}

void newline(std::string& out, int indent) {
  out += '\n';
  out.append(static_cast<std::size_t>(indent), ' ');
}

void write_value(const ojson& v, Sink& sink, int indent) {
  std::string& out = sink.out;
  if (v.is_object()) {
    if (v.empty()) {
      out += "{}";
      return;
    }
    out += '{';
    bool first = true;
    for (const auto& [key, member] : v.get_ref<const ojson::object_t&>()) {
      if (!first) out += ',';
      first = false;
      newline(out, indent + 2);
      write_string(key, out);
      out += ": ";
      write_value(member, sink, indent + 2);
      sink.flush_if_full();
    }
    newline(out, indent);
    out += '}';
  } else if (v.is_array()) {
    if (v.empty()) {
      out += "[]";
      return;
    }
    bool flat = true;
    for (const auto& e : v)
      if (!is_scalar(e)) {
        flat = false;
        break;
      }
    out += '[';
    bool first = true;
    for (const auto& e : v) {
      if (!first) out += flat ? ", " : ",";
      first = false;
      if (!flat) newline(out, indent + 2);
      write_value(e, sink, indent + 2);
      if (!flat) sink.flush_if_full();
    }
    if (!flat) newline(out, indent);
    out += ']';
  } else {
    write_scalar(v, out);
  }
}

}  // namespace

void write_results_json(const ojson& value, std::string& out) {
  Sink sink{out};
  write_value(value, sink, 0);
}

void write_results_json_file(const ojson& value, const std::filesystem::path& path) {
  write_atomic(path, [&](const std::filesystem::path& tmp) {
    std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
    if (!file) throw Error("cannot write '" + tmp.string() + "'");
    std::string buffer;
    buffer.reserve(kChunkBytes + (kChunkBytes >> 4));
    Sink sink{buffer, &file};
    write_value(value, sink, 0);
    buffer += '\n';
    sink.flush();
    file.close();
    if (!file) throw Error("error writing '" + tmp.string() + "'");
  });
}

}  // namespace beamfea
