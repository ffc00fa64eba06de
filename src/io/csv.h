#pragma once
// Reading the text tables of dataset folders (EuRoC csv, TUM and KITTI whitespace tables).
// Lines starting with '#' are comments or headers, blank lines are ignored; every problem is an
// InputError naming the file and the line.
#include <string>
#include <vector>

#include "common/time.h"

namespace vilslam {

struct TableRow {
  long line = 0;  // 1-based line number in the file
  std::vector<std::string> fields;
};

class Table {
 public:
  // separator ',' for csv; ' ' splits on any run of spaces and tabs.
  // Each row must have at least min_fields fields (fewer: "truncated row").
  Table(const std::string& path, char separator, std::size_t min_fields);

  const std::string& path() const { return path_; }
  const std::vector<TableRow>& rows() const { return rows_; }

  // Field parsers: numbers must use the whole field and be finite.
  TimeNs time_ns(const TableRow& row, std::size_t col) const;
  // A time in seconds ("1403715274.30214", "1.4037e+09"), converted to ns exactly (no floating-point rounding).
  TimeNs seconds_as_ns(const TableRow& row, std::size_t col) const;
  double number(const TableRow& row, std::size_t col) const;
  long integer(const TableRow& row, std::size_t col) const;
  const std::string& text(const TableRow& row, std::size_t col) const;

  // Throws unless times (one per row, in row order) increase strictly.
  void require_increasing(const std::vector<TimeNs>& times) const;
  // For files from benchmarks that repeat a stamp now and then (TUM RGB-D ground truth, evo's V102.txt):
  // the indices of the rows to keep. A time equal to the previous kept one drops its row with a warning
  // naming file and line (the first pose at a time is kept, the one evo's association picks); a
  // decreasing time is an InputError as in require_increasing.
  std::vector<std::size_t> rows_without_repeated_times(const std::vector<TimeNs>& times) const;

 private:
  // The whole field as a T (std::from_chars), else InputError "field N is not <what>".
  [[noreturn]] void throw_not_after(const std::vector<TimeNs>& times, std::size_t i, std::size_t previous) const;
  template <typename T>
  T parse(const TableRow& row, std::size_t col, const char* what) const;

  std::string path_;
  std::vector<TableRow> rows_;
};

}  // namespace vilslam
