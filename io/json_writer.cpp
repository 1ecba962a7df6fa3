#include "io/json_writer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <vector>

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

void write_string(std::string_view s, std::string& out) {
  for (const char c : s)
    if (static_cast<unsigned char>(c) >= 0x80) {
      // Non-ASCII: nlohmann's own serialiser (UTF-8 passed through, invalid UTF-8 an error).
      out += ojson(std::string(s)).dump();
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
    default: out += v.dump(); break;  // binary: a deferred part's placeholder whose parts were not given
  }
}

void newline(std::string& out, int indent) {
  out += '\n';
  out.append(static_cast<std::size_t>(indent), ' ');
}

// Writing in slices (write_members_in_slices); docs/performance.md, "The results writer on
// threads", has the measurements (2 cores; a std::thread started and joined in 0.05-0.15 ms):
// - an object or array goes parallel from this many structured members. Cube frames written with
//   the threshold at 32: at 729 nodes and 1,800 elements (6 MB) threads and one thread were level
//   in wall clock, below that threads lost (up to 2x at 0.4 MB; a loaded machine, before the
//   append overlapped the formatting); 1,024 nodes are ~0.25 MB, some 1.5 ms of formatting. An
//   example model's results (tens of nodes) never reach it;
inline constexpr std::size_t kMinParallelMembers = 1024;
// - a window is cut into this many slices: tasks for up to 8 threads, and with fewer threads
//   (2 on the machines measured) pieces small enough that the last one does not hold the others;
inline constexpr std::size_t kSlicesPerWindow = 8;
// - a slice aims at this many bytes, from the mean size of the members written so far: a window
//   of ~2 MB, two of them in memory whatever the size of the file (1 MB slices measured no faster
//   at 21,504 DOFs);
inline constexpr std::size_t kSliceBytes = std::size_t{256} << 10;
// - the first window's slices have this many members (the mean is not known yet), and no slice
//   more than the last (members of a few bytes).
inline constexpr std::size_t kFirstSliceMembers = 16;
inline constexpr std::size_t kMaxSliceMembers = 4096;

// The hook and two windows' slices: one being formatted while the other is written. The strings
// are kept for the whole text (no allocation per window once they have grown to a slice's size).
struct Parallel {
  const ParallelTasks& run;
  std::vector<std::string> slices[2] = {std::vector<std::string>(kSlicesPerWindow), std::vector<std::string>(kSlicesPerWindow)};
};

// What a write reaches besides the value: the hook (null: on this thread; also inside a slice, which
// starts no tasks of its own) and the deferred parts that placeholders stand for (may be null).
struct Writer {
  Parallel* parallel = nullptr;
  const DeferredParts* deferred = nullptr;
};

void write_value(const ojson& v, Sink& sink, int indent, const Writer& w);

// Before member i of an object or array: the comma after the previous member, the line break, the
// indentation and an object's key.
void begin_member(std::size_t i, const std::string_view* key, std::string& out, int indent) {
  if (i > 0) out += ',';
  newline(out, indent + 2);
  if (key) {
    write_string(*key, out);
    out += ": ";
  }
}

// The members of a structured value of the tree, or of a deferred part (made as they are written).
struct Members {
  const ojson* tree = nullptr;
  const DeferredMembers* part = nullptr;
  bool object() const { return part || tree->is_object(); }
  std::size_t size() const { return part ? part->size : tree->size(); }
};

// Members [first, end), each with what goes before it, the stream fed after each.
void write_members(const Members& m, std::size_t first, std::size_t end, Sink& sink, int indent, const Writer& w) {
  if (m.part) {
    std::size_t i = first;
    m.part->make(first, end, [&](std::string_view key, const ojson& value) {
      begin_member(i++, &key, sink.out, indent);
      write_value(value, sink, indent + 2, w);
      sink.flush_if_full();
    });
    return;
  }
  for (std::size_t i = first; i < end; ++i) {
    if (m.tree->is_object()) {
      const auto& [key, member] = *(m.tree->get_ref<const ojson::object_t&>().begin() + static_cast<std::ptrdiff_t>(i));
      const std::string_view k = key;
      begin_member(i, &k, sink.out, indent);
      write_value(member, sink, indent + 2, w);
    } else {
      begin_member(i, nullptr, sink.out, indent);
      write_value(m.tree->get_ref<const ojson::array_t&>()[i], sink, indent + 2, w);
    }
    sink.flush_if_full();
  }
}

// Appends the first `count` slices in order, handing the text to the stream as it fills.
void append_slices(const std::vector<std::string>& slices, std::size_t count, Sink& sink) {
  for (std::size_t s = 0; s < count; ++s) {
    sink.out += slices[s];
    sink.flush_if_full();
  }
}

// The members in windows, each cut into slices that the hook's tasks format into strings of their
// own (serially inside: no nested tasks). One more task appends the previous window's slices to
// the sink meanwhile, so that the stream is fed while the next window is formatted; the last
// window is appended after the loop. The text is the serial one: a member's text depends only on
// its index and indentation, and the windows reach the sink in order.
void write_members_in_slices(const Members& m, Sink& sink, int indent, const Writer& w) {
  Parallel& parallel = *w.parallel;
  const Writer in_slice{nullptr, w.deferred};
  const std::size_t n = m.size();
  std::size_t slice_members = kFirstSliceMembers;
  std::size_t pending = 0;  // slices of the last window formatted, not yet appended
  int current = 0;          // the window formatted next goes into parallel.slices[current]
  for (std::size_t begin = 0; begin < n;) {
    const std::size_t window = std::min(n - begin, slice_members * kSlicesPerWindow);
    const std::size_t per_slice = (window + kSlicesPerWindow - 1) / kSlicesPerWindow;
    const std::size_t slices = (window + per_slice - 1) / per_slice;
    std::vector<std::string>& formatted = parallel.slices[current];
    const std::vector<std::string>& written = parallel.slices[1 - current];
    const std::size_t writer = pending > 0 ? 1 : 0;  // task 0 appends the last window, if any
    parallel.run(writer + slices, [&](std::size_t task) {
      if (task < writer) {
        append_slices(written, pending, sink);
        return;
      }
      const std::size_t s = task - writer;
      // Formatted in a string on this thread's stack (its storage moved in and back out): the
      // strings' headers side by side in `formatted` share cache lines, and appending to them
      // there from two threads cost more than the second thread gained (measured).
      std::string text = std::move(formatted[s]);
      text.clear();
      Sink slice{text};
      const std::size_t first = begin + s * per_slice, end = std::min(begin + window, first + per_slice);
      write_members(m, first, end, slice, indent, in_slice);
      formatted[s] = std::move(text);
    });
    std::size_t bytes = 0;
    for (std::size_t s = 0; s < slices; ++s) bytes += formatted[s].size();
    pending = slices;
    current = 1 - current;
    begin += window;
    slice_members = std::clamp<std::size_t>(kSliceBytes * window / std::max<std::size_t>(bytes, 1), 1, kMaxSliceMembers);
  }
  append_slices(parallel.slices[1 - current], pending, sink);
}

// An object's or array's members between its brackets, one per line.
void write_structured(const Members& m, Sink& sink, int indent, const Writer& w) {
  std::string& out = sink.out;
  const bool object = m.object();
  if (m.size() == 0) {
    out += object ? "{}" : "[]";
    return;
  }
  out += object ? '{' : '[';
  if (w.parallel && m.size() >= kMinParallelMembers)
    write_members_in_slices(m, sink, indent, w);
  else
    write_members(m, 0, m.size(), sink, indent, w);
  newline(out, indent);
  out += object ? '}' : ']';
}

void write_value(const ojson& v, Sink& sink, int indent, const Writer& w) {
  if (const DeferredMembers* part = w.deferred ? w.deferred->find(v) : nullptr) {
    write_structured(Members{nullptr, part}, sink, indent, w);
    return;
  }
  std::string& out = sink.out;
  if (!v.is_structured()) {
    write_scalar(v, out);
    return;
  }
  if (v.is_array() && !v.empty() && std::all_of(v.begin(), v.end(), is_scalar)) {  // on one line
    out += '[';
    bool first = true;
    for (const auto& e : v) {
      if (!first) out += ", ";
      first = false;
      write_scalar(e, out);
    }
    out += ']';
    return;
  }
  write_structured(Members{&v, nullptr}, sink, indent, w);
}

}  // namespace

void write_results_json(const ojson& value, std::string& out, const ParallelTasks& parallel,
                        const DeferredParts* deferred) {
  Sink sink{out};
  std::optional<Parallel> slices;
  if (parallel) slices.emplace(Parallel{parallel});
  write_value(value, sink, 0, Writer{slices ? &*slices : nullptr, deferred});
}

void write_results_json_file(const ojson& value, const std::filesystem::path& path, const ParallelTasks& parallel,
                             const DeferredParts* deferred) {
  write_atomic(path, [&](const std::filesystem::path& tmp) {
    std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
    if (!file) throw Error("cannot write '" + tmp.string() + "'");
    std::string buffer;
    buffer.reserve(kChunkBytes + (kChunkBytes >> 4));
    Sink sink{buffer, &file};
    std::optional<Parallel> slices;
    if (parallel) slices.emplace(Parallel{parallel});
    write_value(value, sink, 0, Writer{slices ? &*slices : nullptr, deferred});
    buffer += '\n';
    sink.flush();
    file.close();
    if (!file) throw Error("error writing '" + tmp.string() + "'");
  });
}

}  // namespace beamfea
