#include "io/json_writer.hpp"

#include <charconv>
#include <cmath>
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

void write_double(double x, std::string& out) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
  for (const char* p = buf; p != r.ptr; ++p)
    if (*p == '.' || *p == 'e') return;
  out += ".0";
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
