#include "io/csv.h"

#include <charconv>
#include <cmath>
#include <fstream>

#include "common/error.h"

namespace vilslam {
namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  const auto end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  if (separator == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      const auto begin = line.find_first_not_of(" \t", i);
      if (begin == std::string::npos) break;
      auto end = line.find_first_of(" \t", begin);
      if (end == std::string::npos) end = line.size();
      fields.push_back(line.substr(begin, end - begin));
      i = end;
    }
    return fields;
  }
  std::size_t begin = 0;
  while (true) {
    const auto end = line.find(separator, begin);
    fields.push_back(trim(line.substr(begin, end == std::string::npos ? std::string::npos : end - begin)));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return fields;
}

}  // namespace

Table::Table(const std::string& path, char separator, std::size_t min_fields) : path_(path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "cannot open file");
  std::string line;
  long number = 0;
  while (std::getline(f, line)) {
    ++number;
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    TableRow row{number, split(content, separator)};
    if (row.fields.size() < min_fields) {
      throw InputError(path, "truncated row: expected " + std::to_string(min_fields) + " fields, got " +
                                 std::to_string(row.fields.size()), number);
    }
    rows_.push_back(std::move(row));
  }
  if (f.bad()) throw InputError(path, "read error");
}

const std::string& Table::text(const TableRow& row, std::size_t col) const {
  if (col >= row.fields.size()) throw InputError(path_, "missing field " + std::to_string(col + 1), row.line);
  if (row.fields[col].empty()) throw InputError(path_, "empty field " + std::to_string(col + 1), row.line);
  return row.fields[col];
}

TimeNs Table::time_ns(const TableRow& row, std::size_t col) const {
  const std::string& s = text(row, col);
  TimeNs t = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), t);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw InputError(path_, "field " + std::to_string(col + 1) + " is not an integer timestamp: '" + s + "'", row.line);
  }
  return t;
}

long Table::integer(const TableRow& row, std::size_t col) const {
  const std::string& s = text(row, col);
  long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw InputError(path_, "field " + std::to_string(col + 1) + " is not an integer: '" + s + "'", row.line);
  }
  return v;
}

double Table::number(const TableRow& row, std::size_t col) const {
  const std::string& s = text(row, col);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw InputError(path_, "field " + std::to_string(col + 1) + " is not a number: '" + s + "'", row.line);
  }
  if (!std::isfinite(v)) {
    throw InputError(path_, "field " + std::to_string(col + 1) + " is not finite: '" + s + "'", row.line);
  }
  return v;
}

TimeNs Table::seconds_as_ns(const TableRow& row, std::size_t col) const {
  const std::string& s = text(row, col);
  const auto dot = s.find('.');
  const std::string whole = s.substr(0, dot);
  const std::string frac = dot == std::string::npos ? std::string() : s.substr(dot + 1);
  const bool plain = !whole.empty() && whole.find_first_not_of("0123456789") == std::string::npos &&
                     frac.find_first_not_of("0123456789") == std::string::npos && whole.size() < 11;
  if (!plain) return s_to_ns(number(row, col));
  // Exact decimal: whole seconds plus the first nine fraction digits, rounded on the tenth.
  TimeNs t = std::stoll(whole) * kNsPerSecond;
  std::string digits = frac.substr(0, 10);
  digits.resize(10, '0');
  const TimeNs frac_tenth_ns = std::stoll(digits);
  return t + (frac_tenth_ns + 5) / 10;
}

void Table::require_increasing(const std::vector<TimeNs>& times) const {
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (times[i] <= times[i - 1]) {
      throw InputError(path_, "timestamp " + std::to_string(times[i]) + " is not after the previous one (" +
                                  std::to_string(times[i - 1]) + ")", rows_[i].line);
    }
  }
}

}  // namespace vilslam
