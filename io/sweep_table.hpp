#pragma once
// The results table of a sweep, DIR/cases.csv (docs/sweep.md): its columns, its rows, reading it
// back (--resume), appending whole rows, and the final sorted rewrite. Only reading and writing:
// the loop that runs the cases and calls these is the program's (app/sweep_runner.hpp); Python
// builds the same columns from the same functions.
//
//   case, <parameters...>, <outputs, arrays flattened: name[i][j]...>, status, message, wall_time_s
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/sweep.hpp"

namespace beamfea {

// RFC 4180: a field quoted when it needs to be; one line split into its fields; cells joined
// into one line (ending in '\n').
std::string csv_field(const std::string& s);
std::vector<std::string> csv_split(const std::string& line);
std::string csv_line(const std::vector<std::string>& cells);

// A JSON scalar as a cell: numbers in the shortest form that reads back to the same double,
// strings without line breaks, null as "".
std::string csv_cell(const nlohmann::json& v);
std::string csv_cell(const ojson& v);
// The same text written over `out` (its capacity kept: a reused cell allocates no more).
void csv_cell_into(std::string& out, const ojson& v);

// The table's columns.
struct SweepColumns {
  std::vector<std::vector<std::string>> outputs;  // per output, its flattened column names
  std::vector<std::string> header(const Sweep& s) const;
};

// Each output's columns are those of `first_ok` (a case that ended ok), or its name alone when
// there is none or it lacks the output.
SweepColumns sweep_columns(const Sweep& s, const SweepCaseResult* first_ok);

// The columns of an existing table; throws InputError when it is not a table of this sweep.
SweepColumns sweep_columns_from_header(const Sweep& s, const std::vector<std::string>& header,
                                       const std::string& table_name);

// A case's row, with its '\n'. Outputs of another shape fill the columns they share.
std::string sweep_row(const Sweep& s, std::size_t index, const SweepColumns& columns, const SweepCaseResult& r);
// The same row appended to `out`.
void append_sweep_row(std::string& out, const Sweep& s, std::size_t index, const SweepColumns& columns,
                      const SweepCaseResult& r);

// Case ids back to case indices (a grid's ids are its indices, a list's its "id"s).
class SweepCaseIndex {
 public:
  explicit SweepCaseIndex(const Sweep& s);
  bool find(const std::string& id, std::size_t& index) const;

 private:
  const Sweep& sweep_;
  std::unordered_map<std::string, std::size_t> ids_;
};

// A table as read back: header and complete rows (a trailing line without '\n' is dropped).
struct SweepTable {
  std::vector<std::string> header;
  std::vector<std::string> rows;  // each with its '\n'
  bool partial_tail = false;
};
SweepTable read_sweep_table(const std::filesystem::path& path);

// What --resume finds in an existing table: its columns and the cases it holds (a partial last
// line, which whole-row writes never leave, is cut off). found = false: no table or no header.
// Throws InputError when the table is not one of this sweep.
struct SweepResume {
  bool found = false;
  SweepColumns columns;
  std::vector<char> done;  // per case index
};
SweepResume resume_sweep_table(const Sweep& s, const std::filesystem::path& table);

// Appends whole rows to an existing table, each batch in one write(2), so that the file is valid
// CSV at every moment. Throws beamfea::Error when the file cannot be opened or written (a full disk,
// a file size limit: the rows written before stay, a torn last one is cut by --resume). A row is safe
// from a kill of the process once append returns, and from a crash of the machine (power loss) once
// synced: fdatasync at most kSyncPeriod apart and when the appender closes.
class SweepTableAppender {
 public:
  explicit SweepTableAppender(std::filesystem::path table);
  ~SweepTableAppender();
  SweepTableAppender(const SweepTableAppender&) = delete;
  SweepTableAppender& operator=(const SweepTableAppender&) = delete;
  void append(const std::string& rows);
  static constexpr std::chrono::seconds kSyncPeriod{1};

 private:
  void sync();
  std::filesystem::path path_;
  int fd_ = -1;
  std::chrono::steady_clock::time_point last_sync_ = std::chrono::steady_clock::now();
};

// Sorts the table by case order, one row per case (the last written wins), rewrites it
// atomically, and counts the statuses.
struct SweepTableCounts {
  std::size_t ok = 0, analysis_failed = 0, bad_input = 0;
};
SweepTableCounts finish_sweep_table(const Sweep& s, const std::filesystem::path& table);

}  // namespace beamfea
