#include "io/sweep_table.hpp"

#include <string_view>

#include <fcntl.h>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace beamfea {

namespace {

// Case ids of a grid are indices; more digits than this cannot be one (and would overflow).
constexpr std::size_t kMaxGridIdDigits = 18;

std::string without_line_breaks(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

template <class J>
std::string cell_text(const J& v) {
  switch (v.type()) {
    case J::value_t::null: return "";
    case J::value_t::boolean: return v.template get<bool>() ? "true" : "false";
    case J::value_t::string: return without_line_breaks(v.template get<std::string>());
    case J::value_t::number_integer: return std::to_string(v.template get<std::int64_t>());
    case J::value_t::number_unsigned: return std::to_string(v.template get<std::uint64_t>());
    case J::value_t::number_float: return fmt::format("{}", v.template get<double>());  // shortest round trip
    default: return v.dump();
  }
}

// Appends x as the compiled format `f` writes it, the digits first into fmt's buffer (on the stack
// up to 500 characters) and then onto the line at once: a sweep formats every number of every
// case's outputs, and a runtime format's parsing and appends one character at a time (a
// std::string back_inserter, or format_to_n's truncating iterator) were most of that cost.
template <class CompiledFormat>
void append_formatted(std::string& line, const CompiledFormat& f, double x) {
  fmt::memory_buffer digits;
  fmt::format_to(fmt::appender(digits), f, x);
  line.append(digits.data(), digits.size());
}

// x as cell_text's fmt::format("{}") writes it (shortest round trip). Digits, a point, a sign, "e",
// "inf" or "nan": a CSV field that never needs quotes.
void append_number(std::string& line, double x) { append_formatted(line, FMT_COMPILE("{}"), x); }

std::string read_text(const std::filesystem::path& path) {
  // One read into a string of the file's size (a stringstream's buffer grows by doubling and its
  // str() copies it again: three passes over a large table's pages).
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  std::string text(static_cast<std::size_t>(std::max<std::streamoff>(0, in.tellg())), '\0');
  in.seekg(0);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  return text;
}

// Field k of a CSV row (its final line break ignored), as csv_split(row)[k] ("" past the last field),
// without splitting the other fields: finishing a table reads two fields of every row.
std::string csv_field_at(std::string_view line, std::size_t k) {
  if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
  if (line.find('"') == std::string_view::npos) {
    // No quotes (a sweep's usual row): the fields lie between commas, found by memchr rather than
    // character by character; '\r' is dropped as below.
    std::size_t begin = 0;
    for (std::size_t field = 0; field < k; ++field) {
      const std::size_t comma = line.find(',', begin);
      if (comma == std::string_view::npos) return std::string();
      begin = comma + 1;
    }
    const std::string_view f = line.substr(begin, line.find(',', begin) - begin);
    std::string out;
    out.reserve(f.size());
    for (char c : f)
      if (c != '\r') out += c;
    return out;
  }
  std::string f;
  std::size_t field = 0;
  bool quoted = false, in_quotes = false, has = false;  // has: the current field has text
  auto put = [&](char c) {
    has = true;
    if (field == k) f += c;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        put('"');
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        put(c);
      }
    } else if (c == '"' && !has && !quoted) {
      in_quotes = quoted = true;
    } else if (c == ',') {
      if (field == k) return f;
      ++field;
      quoted = has = false;
    } else if (c != '\r') {
      put(c);
    }
  }
  return field == k ? f : std::string();
}

std::string first_field(const std::string& row) { return csv_field_at(row, 0); }

}  // namespace

std::string csv_cell(const nlohmann::json& v) { return cell_text(v); }
std::string csv_cell(const ojson& v) { return cell_text(v); }

void csv_cell_into(std::string& out, const ojson& v) {
  if (v.type() != ojson::value_t::number_float) {
    out = cell_text(v);
    return;
  }
  out.clear();
  append_number(out, v.get<double>());
}

namespace {
// Appends s to line as a CSV field (csv_field) without a copy of it.
void append_csv_field(std::string& line, std::string_view s) {
  // One pass over the characters (string_view::find_first_of calls memchr over the set for each one).
  const bool plain = std::none_of(s.begin(), s.end(), [](char c) { return c == ',' || c == '"' || c == '\n' || c == '\r'; });
  if (plain) {
    line += s;
    return;
  }
  line += '"';
  for (char c : s) {
    if (c == '"') line += '"';
    line += c;
  }
  line += '"';
}
}  // namespace

std::string csv_field(const std::string& s) {
  std::string q;
  append_csv_field(q, s);
  return q;
}

std::vector<std::string> csv_split(const std::string& line) {
  std::vector<std::string> out;
  std::string f;
  bool quoted = false, in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        f += c;
      }
    } else if (c == '"' && f.empty() && !quoted) {
      in_quotes = quoted = true;
    } else if (c == ',') {
      out.push_back(std::move(f));
      f.clear();
      quoted = false;
    } else if (c != '\r') {
      f += c;
    }
  }
  out.push_back(std::move(f));
  return out;
}

std::string csv_line(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line += ',';
    append_csv_field(line, cells[i]);
  }
  line += '\n';
  return line;
}

// ---------------------------------------------------------------------------------------------
// Columns and rows

std::vector<std::string> SweepColumns::header(const Sweep& s) const {
  std::vector<std::string> h{"case"};
  h.insert(h.end(), s.parameter_names.begin(), s.parameter_names.end());
  for (const auto& o : outputs) h.insert(h.end(), o.begin(), o.end());
  h.insert(h.end(), {"status", "message", "wall_time_s"});
  return h;
}

SweepColumns sweep_columns(const Sweep& s, const SweepCaseResult* first_ok) {
  SweepColumns c;
  c.outputs.resize(s.outputs.size());
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    if (first_ok && o < first_ok->outputs.size() && !first_ok->outputs[o].empty())
      for (const auto& kv : first_ok->outputs[o]) c.outputs[o].push_back(kv.first);
    else
      c.outputs[o].push_back(s.outputs[o].name);
  }
  return c;
}

SweepColumns sweep_columns_from_header(const Sweep& s, const std::vector<std::string>& h, const std::string& table) {
  const std::size_t P = s.parameter_names.size();
  auto differ = [&](const std::string& why) {
    return InputError("", "--resume: " + table + " is not a table of this sweep (" + why + "); remove it or use another --out");
  };
  if (h.size() < 4 + P || h[0] != "case" || h[h.size() - 3] != "status" || h[h.size() - 2] != "message" ||
      h.back() != "wall_time_s")
    throw differ("unexpected columns");
  for (std::size_t i = 0; i < P; ++i)
    if (h[1 + i] != s.parameter_names[i]) throw differ("parameter column '" + h[1 + i] + "'");
  SweepColumns c;
  std::size_t k = 1 + P;
  const std::size_t end = h.size() - 3;
  for (const auto& o : s.outputs) {
    std::vector<std::string> mine;
    while (k < end && (h[k] == o.name || h[k].rfind(o.name + "[", 0) == 0 || h[k].rfind(o.name + ".", 0) == 0))
      mine.push_back(h[k++]);
    if (mine.empty()) throw differ("no column for output '" + o.name + "'");
    c.outputs.push_back(std::move(mine));
  }
  if (k != end) throw differ("column '" + h[k] + "' is not an output of this sweep");
  return c;
}

std::string sweep_row(const Sweep& s, std::size_t index, const SweepColumns& cols, const SweepCaseResult& r) {
  std::string line;
  append_sweep_row(line, s, index, cols, r);
  return line;
}

void append_sweep_row(std::string& line, const Sweep& s, std::size_t index, const SweepColumns& cols,
                      const SweepCaseResult& r) {
  // Written field by field onto the line (csv_line's format), without a vector of cell copies.
  bool first = true;
  auto add = [&](std::string_view cell) {
    if (!first) line += ',';
    first = false;
    append_csv_field(line, cell);
  };
  add(s.case_id(index));
  for (std::size_t k = 0; k < s.parameter_names.size(); ++k) {  // read in place, not copied
    const nlohmann::json& p = s.parameter(index, k);
    if (p.type() == nlohmann::json::value_t::number_float) {  // the usual parameter: onto the line
      add("");
      append_number(line, p.get<double>());
    } else {
      add(p.is_null() ? "" : cell_text(p));
    }
  }
  for (std::size_t o = 0; o < cols.outputs.size(); ++o) {
    const auto& names = cols.outputs[o];
    static const std::vector<std::pair<std::string, std::string>> none;
    const auto& got = o < r.outputs.size() ? r.outputs[o] : none;
    bool same = got.size() == names.size();
    for (std::size_t k = 0; same && k < names.size(); ++k) same = got[k].first == names[k];
    if (same) {
      for (const auto& g : got) add(g.second);
      continue;
    }
    std::unordered_map<std::string, const std::string*> byname;
    for (const auto& g : got) byname.emplace(g.first, &g.second);
    for (const auto& n : names) {
      auto it = byname.find(n);
      add(it == byname.end() ? std::string_view() : std::string_view(*it->second));
    }
  }
  add(to_string(r.status));
  // The message as is unless it has line breaks (a copy then): most cases have none.
  if (r.message.find_first_of("\n\r") == std::string::npos) add(r.message);
  else add(without_line_breaks(r.message));
  line += ',';  // digits, a point and maybe a sign: no quoting
  append_formatted(line, FMT_COMPILE("{:.6f}"), r.wall_time_s);
  line += '\n';
}

// ---------------------------------------------------------------------------------------------
// Case ids

SweepCaseIndex::SweepCaseIndex(const Sweep& s) : sweep_(s) {
  if (s.grid.empty())
    for (std::size_t i = 0; i < s.list.size(); ++i) ids_.emplace(s.list[i].id, i);
}

bool SweepCaseIndex::find(const std::string& id, std::size_t& index) const {
  if (!sweep_.grid.empty()) {
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos || id.size() > kMaxGridIdDigits)
      return false;
    index = std::stoull(id);
    return index < sweep_.size();
  }
  auto it = ids_.find(id);
  if (it == ids_.end()) return false;
  index = it->second;
  return true;
}

// ---------------------------------------------------------------------------------------------
// The file

namespace {
// The header and the rows (views into `text`, each with its '\n') of a table's text; a last line
// without a line break is not a row (returns true then).
bool split_table(const std::string& text, std::vector<std::string>& header, std::vector<std::string_view>& rows) {
  std::size_t pos = 0;
  bool first = true;
  while (pos < text.size()) {
    const auto nl = text.find('\n', pos);
    if (nl == std::string::npos) return true;
    const std::string_view line(text.data() + pos, nl - pos + 1);
    pos = nl + 1;
    if (first) {
      header = csv_split(std::string(line.substr(0, line.size() - 1)));
      first = false;
    } else if (line.size() > 1) {
      rows.push_back(line);
    }
  }
  return false;
}
}  // namespace

SweepTable read_sweep_table(const std::filesystem::path& path) {
  SweepTable t;
  const std::string text = read_text(path);
  std::vector<std::string_view> rows;
  t.partial_tail = split_table(text, t.header, rows);
  t.rows.assign(rows.begin(), rows.end());
  return t;
}

SweepResume resume_sweep_table(const Sweep& s, const std::filesystem::path& table) {
  SweepResume r;
  r.done.assign(s.size(), 0);
  if (!std::filesystem::exists(table)) return r;
  SweepTable t = read_sweep_table(table);
  if (t.header.empty()) return r;
  r.columns = sweep_columns_from_header(s, t.header, table.string());
  r.found = true;
  const SweepCaseIndex index(s);
  for (const auto& row : t.rows) {
    std::size_t i;
    if (!index.find(first_field(row), i))
      throw InputError("", "--resume: " + table.string() + " has a row for case '" + first_field(row) +
                               "', which is not in this sweep");
    r.done[i] = 1;
  }
  if (t.partial_tail) {  // cannot happen with whole-row writes; repair anyway
    std::string text = csv_line(t.header);
    for (const auto& row : t.rows) text += row;
    write_text_atomic(table, text);
  }
  return r;
}

SweepTableAppender::SweepTableAppender(std::filesystem::path table) : path_(std::move(table)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) throw Error("cannot append to '" + path_.string() + "': " + std::strerror(errno));
}

SweepTableAppender::~SweepTableAppender() {
  if (fd_ < 0) return;
  ::fdatasync(fd_);  // best effort here: the table is rewritten (and synced) when the sweep ends
  ::close(fd_);
}

void SweepTableAppender::append(const std::string& rows) {
  const char* p = rows.data();
  std::size_t left = rows.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error("error writing '" + path_.string() + "': " + std::strerror(errno) +
                  "; the rows written before are kept, and --resume runs the others");
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // Each batch is in the kernel once write(2) returns: a killed process loses no row. A crash of the
  // machine loses what the disk has not got yet: flushed at most kSyncPeriod apart (and at the end).
  const auto now = std::chrono::steady_clock::now();
  if (now - last_sync_ >= kSyncPeriod) {
    sync();
    last_sync_ = now;
  }
}

void SweepTableAppender::sync() {
  if (::fdatasync(fd_) != 0 && errno != EINVAL && errno != EROFS)  // EINVAL, EROFS: a file that cannot be synced
    throw Error("error writing '" + path_.string() + "': " + std::strerror(errno) +
                "; the rows written before are kept, and --resume runs the others");
}

SweepTableCounts finish_sweep_table(const Sweep& s, const std::filesystem::path& table) {
  // The rows stay views into the file's text (no string per row): the whole table is re-read once.
  const std::string old_text = read_text(table);
  std::vector<std::string> header;
  std::vector<std::string_view> table_rows;
  split_table(old_text, header, table_rows);
  const SweepCaseIndex index(s);
  std::vector<std::pair<std::size_t, std::string_view>> rows;
  rows.reserve(table_rows.size());
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> where(s.size(), kNone);  // case index -> its row in `rows`
  for (const auto row : table_rows) {
    std::size_t i;
    if (!index.find(csv_field_at(row, 0), i)) continue;
    if (where[i] == kNone) {
      where[i] = rows.size();
      rows.emplace_back(i, row);
    } else {
      rows[where[i]].second = row;  // the last row of a case wins
    }
  }
  std::sort(rows.begin(), rows.end());
  SweepTableCounts counts;
  const std::size_t status_col = header.size() >= 3 ? header.size() - 3 : 0;
  for (const auto& [i, row] : rows) {
    const std::string status = csv_field_at(row, status_col);
    if (status == to_string(SweepCaseResult::Status::Succeeded)) ++counts.ok;
    else if (status == to_string(SweepCaseResult::Status::BadInput)) ++counts.bad_input;
    else ++counts.analysis_failed;
  }
  // The sorted table: the header as csv_line writes it, then the rows. Where the file is that
  // already (a fresh `--jobs 1` run: rows in order, one per case, each following the last in the
  // file's text, nothing after them), its atomic rewrite (a copy, a sync, a rename) would change
  // nothing, and the text is not built.
  const std::string head = csv_line(header);
  bool same = old_text.size() >= head.size() && old_text.compare(0, head.size(), head) == 0;
  std::size_t at = head.size();  // where the next row must start in the file's text
  for (std::size_t k = 0; same && k < rows.size(); ++k) {
    same = rows[k].second.data() == old_text.data() + at;
    at += rows[k].second.size();
  }
  if (same && at == old_text.size()) return counts;
  std::string text = head;
  text.reserve(old_text.size());
  for (const auto& r : rows) text += r.second;
  write_text_atomic(table, text);
  return counts;
}

}  // namespace beamfea
